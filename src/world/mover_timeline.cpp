#include "world/mover_timeline.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include <btBulletDynamicsCommon.h>
#include <BulletCollision/CollisionDispatch/btInternalEdgeUtility.h>

#include "world/movers.hpp"

namespace peg3d::world {
namespace {

btVector3 bt(const Vec3& v) { return {v.x(), v.y(), v.z()}; }
Vec3 vec(const btVector3& v) { return {v.x(), v.y(), v.z()}; }
btTransform bt(const Pose& p) {
  return btTransform(btQuaternion(p.orientation.x(), p.orientation.y(), p.orientation.z(), p.orientation.w()),
                     bt(p.position));
}
Pose pose_of(const btTransform& t) {
  const btQuaternion q = t.getRotation();
  return {vec(t.getOrigin()), Quat(q.w(), q.x(), q.y(), q.z())};
}

std::unique_ptr<btCollisionShape> shape_of(const Shape& s) {
  switch (s.kind) {
    case Shape::Kind::kSphere: return std::make_unique<btSphereShape>(s.radius);
    case Shape::Kind::kCylinder: {
      auto c = std::make_unique<btCylinderShapeZ>(btVector3(s.radius, s.radius, 0.5 * s.height));
      c->setMargin(std::min(0.01, 0.25 * std::min(s.radius, 0.5 * s.height)));
      return c;
    }
    case Shape::Kind::kBox: {
      auto b = std::make_unique<btBoxShape>(bt(0.5 * s.size));
      b->setMargin(std::min(0.01, 0.25 * s.size.minCoeff()));
      return b;
    }
  }
  return nullptr;
}

// Triangle meshes get smooth contacts across their internal edges (a rolling ball would hop at every edge).
bool adjust_internal_edges(btManifoldPoint& cp, const btCollisionObjectWrapper* w0, int part0, int index0,
                           const btCollisionObjectWrapper* w1, int part1, int index1) {
  if (w1->getCollisionShape()->getShapeType() == TRIANGLE_SHAPE_PROXYTYPE) {
    btAdjustInternalEdgeContacts(cp, w1, w0, part1, index1);
  } else if (w0->getCollisionShape()->getShapeType() == TRIANGLE_SHAPE_PROXYTYPE) {
    btAdjustInternalEdgeContacts(cp, w0, w1, part0, index0);
  }
  return false;
}

// One Bullet dynamics world holding a map's static geometry and its movers, stepped at the map's rate.
class Physics {
 public:
  Physics(const MapSpec& spec, const std::vector<TriangleMesh>& meshes) {
    world_.setGravity(bt(spec.physics.gravity));
    // Static bodies: friction and restitution 1, so that a contact's combined values (Bullet multiplies the
    // two bodies') are the mover's own.
    for (const SphereObstacle& s : spec.spheres) add_static(std::make_unique<btSphereShape>(s.radius), s.center);
    for (const CylinderObstacle& c : spec.cylinders) {
      auto shape = std::make_unique<btCylinderShapeZ>(btVector3(c.radius, c.radius, 0.5 * c.height));
      shape->setMargin(std::min(0.005, 0.25 * std::min(c.radius, 0.5 * c.height)));
      add_static(std::move(shape), c.base + Vec3(0, 0, 0.5 * c.height));
    }
    for (const TriangleMesh& m : meshes) {
      if (m.faces.empty()) continue;
      auto array = std::make_unique<btTriangleIndexVertexArray>(
          int(m.faces.size()), const_cast<int*>(m.faces.front().data()), int(sizeof(m.faces[0])),
          int(m.vertices.size()), const_cast<btScalar*>(m.vertices.front().data()), int(sizeof(Vec3)));
      auto shape = std::make_unique<btBvhTriangleMeshShape>(array.get(), true);
      auto info = std::make_unique<btTriangleInfoMap>();
      btGenerateInternalEdgeInfo(shape.get(), info.get());
      btRigidBody* body = add_static(std::move(shape), Vec3::Zero());
      body->setCollisionFlags(body->getCollisionFlags() | btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK);
      arrays_.push_back(std::move(array));
      infos_.push_back(std::move(info));
      gContactAddedCallback = adjust_internal_edges;
    }
    if (spec.physics.faces_are_physical) {
      const Box& b = spec.bounds;
      for (int axis = 0; axis < 3; ++axis) {
        Vec3 n = Vec3::Zero();
        n[axis] = 1.0;  // inward at the low face: n . x = lo
        add_static(std::make_unique<btStaticPlaneShape>(bt(n), b.lo[axis]), Vec3::Zero());
        add_static(std::make_unique<btStaticPlaneShape>(bt(Vec3(-n)), -b.hi[axis]), Vec3::Zero());
      }
    }
    for (const MoverSpec& m : spec.movers) add_mover(m);
  }

  ~Physics() {
    for (auto& b : bodies_) world_.removeRigidBody(b.get());
  }

  // Moves the scripted movers to their poses at `t_next` and steps the world by h.
  void step(double t_next, double h) {
    for (std::size_t i = 0; i < movers_.size(); ++i) {
      if (!movers_[i].spec->kinematic()) continue;
      movers_[i].state->setWorldTransform(bt(scripted_pose(*movers_[i].spec, t_next)));
    }
    world_.stepSimulation(h, 1, h);
  }

  Pose pose(std::size_t mover) const { return pose_of(movers_[mover].body->getWorldTransform()); }

 private:
  struct Mover {
    const MoverSpec* spec;
    btRigidBody* body;
    btDefaultMotionState* state;
  };

  btRigidBody* add_static(std::unique_ptr<btCollisionShape> shape, const Vec3& at) {
    btRigidBody::btRigidBodyConstructionInfo info(0.0, nullptr, shape.get());
    info.m_startWorldTransform = btTransform(btQuaternion::getIdentity(), bt(at));
    info.m_friction = 1.0;
    info.m_restitution = 1.0;
    auto body = std::make_unique<btRigidBody>(info);
    world_.addRigidBody(body.get());
    btRigidBody* raw = body.get();
    shapes_.push_back(std::move(shape));
    bodies_.push_back(std::move(body));
    return raw;
  }

  void add_mover(const MoverSpec& m) {
    auto shape = shape_of(m.shape);
    const Pose start = m.kinematic() ? scripted_pose(m, 0.0) : Pose{m.start, orientation_deg(m.rotation_deg)};
    auto state = std::make_unique<btDefaultMotionState>(bt(start));
    const double mass = m.kinematic() ? 0.0 : m.dynamic.mass;
    btVector3 inertia(0, 0, 0);
    if (mass > 0.0) shape->calculateLocalInertia(mass, inertia);
    btRigidBody::btRigidBodyConstructionInfo info(mass, state.get(), shape.get(), inertia);
    info.m_friction = m.kinematic() ? 1.0 : m.dynamic.friction;
    info.m_rollingFriction = m.kinematic() ? 0.0 : m.dynamic.rolling_friction;
    info.m_restitution = m.kinematic() ? 1.0 : m.dynamic.restitution;
    auto body = std::make_unique<btRigidBody>(info);
    if (m.kinematic()) {
      body->setCollisionFlags(body->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
      body->setActivationState(DISABLE_DEACTIVATION);
    } else {
      body->setLinearVelocity(bt(m.dynamic.velocity));
      body->setAngularVelocity(bt(m.dynamic.angular_velocity));
      // Continuous collision for fast bodies: a sweep whenever a substep moves them more than a tenth of their size.
      const double size = m.shape.kind == Shape::Kind::kBox ? 0.5 * m.shape.size.minCoeff() : m.shape.radius;
      body->setCcdMotionThreshold(0.1 * size);
      body->setCcdSweptSphereRadius(0.9 * size);
    }
    world_.addRigidBody(body.get());
    movers_.push_back({&m, body.get(), state.get()});
    shapes_.push_back(std::move(shape));
    states_.push_back(std::move(state));
    bodies_.push_back(std::move(body));
  }

  btDefaultCollisionConfiguration configuration_;
  btCollisionDispatcher dispatcher_{&configuration_};
  btDbvtBroadphase broadphase_;
  btSequentialImpulseConstraintSolver solver_;
  btDiscreteDynamicsWorld world_{&dispatcher_, &broadphase_, &solver_, &configuration_};
  std::vector<std::unique_ptr<btCollisionShape>> shapes_;
  std::vector<std::unique_ptr<btTriangleIndexVertexArray>> arrays_;
  std::vector<std::unique_ptr<btTriangleInfoMap>> infos_;
  std::vector<std::unique_ptr<btDefaultMotionState>> states_;
  std::vector<std::unique_ptr<btRigidBody>> bodies_;
  std::vector<Mover> movers_;
};

// The rotation angle between two orientations, rad.
double angle_between(const Quat& a, const Quat& b) { return a.angularDistance(b); }

}  // namespace

MoverTimeline::MoverTimeline(const MapSpec& spec, const std::vector<TriangleMesh>& meshes, double duration)
    : movers_(spec.movers), rate_hz_(spec.physics.rate_hz) {
  const double h = 1.0 / rate_hz_;
  substeps_ = static_cast<long>(std::ceil(duration * rate_hz_ - 1e-9));
  duration_ = substeps_ * h;
  dynamic_index_.assign(movers_.size(), -1);
  for (std::size_t i = 0; i < movers_.size(); ++i) {
    if (movers_[i].kinematic()) continue;
    dynamic_index_[i] = static_cast<int>(poses_.size());
    poses_.emplace_back();
    poses_.back().reserve(std::size_t(substeps_) + 1);
  }
  if (poses_.empty()) return;  // scripted movers only: nothing to simulate
  Physics physics(spec, meshes);
  const auto record = [&] {
    for (std::size_t i = 0; i < movers_.size(); ++i) {
      if (dynamic_index_[i] >= 0) poses_[std::size_t(dynamic_index_[i])].push_back(physics.pose(i));
    }
  };
  record();
  for (long k = 0; k < substeps_; ++k) {
    physics.step((k + 1) * h, h);
    record();
  }
}

Pose MoverTimeline::pose(int m, double t) const {
  const MoverSpec& spec = movers_[std::size_t(m)];
  if (spec.kinematic()) return scripted_pose(spec, t);
  const std::vector<Pose>& row = poses_[std::size_t(dynamic_index_[std::size_t(m)])];
  if (substeps_ == 0) return row.front();
  const double u = std::clamp(t * rate_hz_, 0.0, static_cast<double>(substeps_));
  const long k = std::min(static_cast<long>(u), substeps_ - 1);
  const double s = u - static_cast<double>(k);
  const Pose& a = row[std::size_t(k)];
  const Pose& b = row[std::size_t(k + 1)];
  // A ball's orientation does not change where its points are: skip the spherical interpolation.
  if (spec.shape.kind == Shape::Kind::kSphere) return {a.position + s * (b.position - a.position), a.orientation};
  return interpolate(a, b, s);
}

double MoverTimeline::travel_bound(int m, double t0, double t1) const {
  const MoverSpec& spec = movers_[std::size_t(m)];
  if (spec.kinematic()) return scripted_speed(spec) * (t1 - t0);  // orientation is fixed
  const std::vector<Pose>& row = poses_[std::size_t(dynamic_index_[std::size_t(m)])];
  const double r = spec.shape.bounding_radius();
  const long k0 = std::clamp(static_cast<long>(std::floor(t0 * rate_hz_)), 0L, substeps_);
  const long k1 = std::clamp(static_cast<long>(std::ceil(t1 * rate_hz_)), 0L, substeps_);
  // Any point of the body: its centre's path plus the arc its farthest point sweeps, substep by substep.
  double bound = 0.0;
  for (long k = k0; k < k1; ++k) {
    const Pose& a = row[std::size_t(k)];
    const Pose& b = row[std::size_t(k + 1)];
    bound += (b.position - a.position).norm() + angle_between(a.orientation, b.orientation) * r;
  }
  return bound;
}

MoverPoint MoverTimeline::nearest(const Vec3& p, double t, double cap) const {
  MoverPoint best;
  best.distance = cap;
  for (int m = 0; m < count(); ++m) {
    const MoverSpec& spec = movers_[std::size_t(m)];
    const Pose at = pose(m, t);
    // Cheap rejection on the bounding ball before the exact distance.
    if ((p - at.position).norm() - spec.shape.bounding_radius() >= best.distance) continue;
    const ShapePoint s = nearest_on_shape(spec.shape, at, p);
    if (s.distance < best.distance) best = {m, s.distance, s.point};
  }
  return best;
}

std::optional<MoverContact> MoverTimeline::first_contact(const Vec3& from, const Vec3& to, double radius, double t0,
                                                         double dt) const {
  std::optional<MoverContact> best;
  const double agent_travel = (to - from).norm();
  for (int m = 0; m < count(); ++m) {
    const MoverSpec& spec = movers_[std::size_t(m)];
    const double mover_travel = travel_bound(m, t0, t0 + dt);
    const double closing = agent_travel + mover_travel;  // relative travel over the whole step: a bound
    // Rejection: too far apart for the step to close the gap.
    const Pose p0 = pose(m, t0);
    if ((from - p0.position).norm() - spec.shape.bounding_radius() - radius > closing + kContactTolerance) continue;
    // Conservative advancement: at s (fraction of the step) the gap g(s) can shrink by at most closing * ds, so
    // advancing by g / closing never skips a contact, however fast the two move.
    double s = 0.0;
    for (int iteration = 0; iteration < 100000 && s <= 1.0; ++iteration) {
      const Vec3 c = from + s * (to - from);
      const Pose at = pose(m, t0 + s * dt);
      const double signed_gap = signed_distance(spec.shape, at, c) - radius;
      if (signed_gap <= kContactTolerance) {
        if (best && best->fraction <= s) break;
        const ShapePoint sp = nearest_on_shape(spec.shape, at, c);
        Vec3 normal = c - sp.point;
        if (normal.norm() == 0.0) normal = c - at.position;  // centre inside the shape: away from its centre
        normal = normal.norm() > 0.0 ? Vec3(normal.normalized()) : Vec3(Vec3::UnitZ());
        MoverContact contact;
        contact.mover = m;
        contact.fraction = s;
        contact.point = sp.distance > 0.0 ? sp.point : Vec3(c - radius * normal);
        contact.normal = normal;
        contact.penetration = s == 0.0 ? std::max(0.0, -signed_gap) : 0.0;
        best = contact;
        break;
      }
      if (closing <= 0.0) break;  // neither moves: the gap stays
      s += signed_gap / closing;
      if (best && s >= best->fraction) break;  // cannot beat a contact already found
    }
  }
  return best;
}

}  // namespace peg3d::world
