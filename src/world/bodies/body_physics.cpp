#include "world/bodies/body_physics.hpp"

#include <algorithm>
#include <cassert>
#include <limits>

#include <btBulletDynamicsCommon.h>
#include <BulletCollision/CollisionDispatch/btGhostObject.h>
#include <BulletCollision/CollisionDispatch/btInternalEdgeUtility.h>

#include "world/map/movers.hpp"

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

// Collision groups of push mode, bits above Bullet's own (btBroadphaseProxy::CollisionFilterGroups).
constexpr int kPushableGroup = 1 << 8;
constexpr int kSolidGroup = 1 << 9;
constexpr int kAgentGroup = 1 << 10;
constexpr int kSensorGroup = 1 << 11;

}  // namespace

struct StaticPhysicsShapes {
  struct Static {
    std::unique_ptr<btCollisionShape> shape;
    Vec3 at = Vec3::Zero();
    bool mesh = false;  ///< a terrain hierarchy: contacts go through adjust_internal_edges
  };
  std::vector<Static> statics;  ///< in the order the bodies are added: spheres, cylinders, meshes, faces
  std::vector<std::unique_ptr<btTriangleIndexVertexArray>> arrays;
  std::vector<std::unique_ptr<btTriangleInfoMap>> infos;
};

std::shared_ptr<const StaticPhysicsShapes> make_static_physics_shapes(const MapSpec& spec,
                                                                      const std::vector<TriangleMesh>& meshes) {
  auto s = std::make_shared<StaticPhysicsShapes>();
  for (const SphereObstacle& o : spec.spheres) s->statics.push_back({std::make_unique<btSphereShape>(o.radius), o.center});
  for (const CylinderObstacle& c : spec.cylinders) {
    auto shape = std::make_unique<btCylinderShapeZ>(btVector3(c.radius, c.radius, 0.5 * c.height));
    shape->setMargin(std::min(0.005, 0.25 * std::min(c.radius, 0.5 * c.height)));
    s->statics.push_back({std::move(shape), c.base + Vec3(0, 0, 0.5 * c.height)});
  }
  for (const TriangleMesh& m : meshes) {
    if (m.faces.empty()) continue;
    auto array = std::make_unique<btTriangleIndexVertexArray>(
        int(m.faces.size()), const_cast<int*>(m.faces.front().data()), int(sizeof(m.faces[0])),
        int(m.vertices.size()), const_cast<btScalar*>(m.vertices.front().data()), int(sizeof(Vec3)));
    auto shape = std::make_unique<btBvhTriangleMeshShape>(array.get(), true);
    auto info = std::make_unique<btTriangleInfoMap>();
    btGenerateInternalEdgeInfo(shape.get(), info.get());
    s->statics.push_back({std::move(shape), Vec3::Zero(), true});
    s->arrays.push_back(std::move(array));
    s->infos.push_back(std::move(info));
    gContactAddedCallback = adjust_internal_edges;
  }
  if (spec.physics.faces_are_physical) {
    const Box& b = spec.bounds;
    for (int axis = 0; axis < 3; ++axis) {
      Vec3 n = Vec3::Zero();
      n[axis] = 1.0;  // inward at the low face: n . x = lo
      s->statics.push_back({std::make_unique<btStaticPlaneShape>(bt(n), b.lo[axis]), Vec3::Zero()});
      s->statics.push_back({std::make_unique<btStaticPlaneShape>(bt(Vec3(-n)), -b.hi[axis]), Vec3::Zero()});
    }
  }
  return s;
}

struct BodyPhysics::Impl {
  struct Mover {
    const MoverSpec* spec;
    btRigidBody* body;
    btDefaultMotionState* state;
    ScriptedMotion motion;  ///< a path's or orbit's; unused for a dynamic body
  };
  struct Agent {
    std::unique_ptr<btSphereShape> shape, sensor_shape;
    std::unique_ptr<btDefaultMotionState> state;
    std::unique_ptr<btRigidBody> body;
    std::unique_ptr<btPairCachingGhostObject> sensor;
    bool in_world = true;
  };

  Impl(const MapSpec& spec, std::shared_ptr<const StaticPhysicsShapes> s, const std::vector<MoverSpec>& movers, bool p)
      : statics(std::move(s)), push(p) {
    world.setGravity(bt(spec.physics.gravity));
    if (push) {
      broadphase.getOverlappingPairCache()->setInternalGhostPairCallback(&ghost_pairs);
      // Sleeping bodies keep their bounds: a world of resting bodies around agents costs what its awake part does.
      world.setForceUpdateAllAabbs(false);
      // Every overlap is pushed apart by split impulse (positions corrected without velocity). A contact is found
      // only once the bodies overlap, by as much as their relative travel since the touch within the substep;
      // Bullet's default turns an overlap shallower than 4 cm into velocity (erp 0.2 of it per substep), so a
      // hit's outgoing speed grew with where in the substep it fell (up to 0.2 of the normal speed) and a pair
      // of restitution 1 gained energy. The shared timeline keeps the default: its motion stays as it was.
      btContactSolverInfo& solver = world.getSolverInfo();
      solver.m_splitImpulse = 1;
      solver.m_splitImpulsePenetrationThreshold = std::numeric_limits<btScalar>::infinity();
    }
    // Static bodies: friction and restitution 1, so that a contact's combined values (Bullet multiplies the
    // two bodies') are the mover's own.
    for (const StaticPhysicsShapes::Static& st : statics->statics) {
      btRigidBody::btRigidBodyConstructionInfo info(0.0, nullptr, st.shape.get());
      info.m_startWorldTransform = btTransform(btQuaternion::getIdentity(), bt(st.at));
      info.m_friction = 1.0;
      info.m_restitution = 1.0;
      auto body = std::make_unique<btRigidBody>(info);
      body->setUserIndex(-1);
      if (st.mesh) body->setCollisionFlags(body->getCollisionFlags() | btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK);
      world.addRigidBody(body.get());
      bodies.push_back(std::move(body));
    }
    for (const MoverSpec& m : movers) add_mover(m);
  }

  ~Impl() {
    for (Agent& a : agents) {
      if (!a.in_world) continue;
      world.removeRigidBody(a.body.get());
      world.removeCollisionObject(a.sensor.get());
    }
    for (auto& b : bodies) world.removeRigidBody(b.get());
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
    body->setUserIndex(static_cast<int>(movers_.size()));
    if (m.kinematic()) {
      body->setCollisionFlags(body->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
      body->setActivationState(DISABLE_DEACTIVATION);
      world.addRigidBody(body.get());
    } else {
      body->setLinearVelocity(bt(m.dynamic.velocity));
      body->setAngularVelocity(bt(m.dynamic.angular_velocity));
      // Continuous collision for fast bodies: a sweep whenever a substep moves them more than a tenth of their size.
      const double size = m.shape.kind == Shape::Kind::kBox ? 0.5 * m.shape.size.minCoeff() : m.shape.radius;
      body->setCcdMotionThreshold(0.1 * size);
      body->setCcdSweptSphereRadius(0.9 * size);
      if (push) {
        // Bullet's default group and mask for a dynamic body, with the touch's bit added.
        const int touch = m.dynamic.touch == DynamicMotion::Touch::kPushable ? kPushableGroup : kSolidGroup;
        world.addRigidBody(body.get(), btBroadphaseProxy::DefaultFilter | touch, btBroadphaseProxy::AllFilter);
      } else {
        world.addRigidBody(body.get());
      }
    }
    movers_.push_back({&m, body.get(), state.get(), ScriptedMotion(m)});
    shapes.push_back(std::move(shape));
    states.push_back(std::move(state));
    bodies.push_back(std::move(body));
  }

  void step(double t_next, double h) {
    if (still) return;
    bool kinematic = !agents.empty(), scripted = false, awake = false;
    for (Mover& m : movers_) {
      if (m.spec->kinematic()) {
        m.state->setWorldTransform(bt(m.motion.pose(t_next)));
        kinematic = scripted = true;
      } else {
        awake = awake || m.body->getActivationState() != ISLAND_SLEEPING;
      }
    }
    if (!kinematic && !awake) {
      still = true;
      return;
    }
    if (!scripted && !awake && !agents.empty() && !agent_near_body()) {
      // Every body sleeps and no agent comes near one: a step would change nothing but the agents' places.
      for (Agent& a : agents) {
        if (!a.in_world) continue;
        btTransform t;
        a.state->getWorldTransform(t);
        a.body->setWorldTransform(t);
        a.body->setInterpolationWorldTransform(t);  // the next step's velocity is that substep's move alone
        a.sensor->setWorldTransform(t);
      }
      return;
    }
    world.stepSimulation(h, 1, h);
  }

  // Whether any agent's sensor, where it is about to be, overlaps a dynamic body's bounds.
  bool agent_near_body() {
    struct Any : btBroadphaseAabbCallback {
      bool found = false;
      bool process(const btBroadphaseProxy* proxy) override {
        const auto* object = static_cast<const btCollisionObject*>(proxy->m_clientObject);
        if (object->getUserIndex() >= 0 && !object->isStaticOrKinematicObject()) found = true;
        return !found;
      }
    };
    for (const Agent& a : agents) {
      if (!a.in_world) continue;
      btTransform t;
      a.state->getWorldTransform(t);
      btVector3 lo, hi;
      a.sensor_shape->getAabb(t, lo, hi);
      Any any;
      broadphase.aabbTest(lo, hi, any);
      if (any.found) return true;
    }
    return false;
  }

  std::shared_ptr<const StaticPhysicsShapes> statics;
  bool push = false;
  btDefaultCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher{&configuration};
  btDbvtBroadphase broadphase;
  btGhostPairCallback ghost_pairs;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &configuration};
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btDefaultMotionState>> states;
  std::vector<std::unique_ptr<btRigidBody>> bodies;
  std::vector<Mover> movers_;
  std::vector<Agent> agents;
  bool still = false;  ///< every body sleeps and nothing moves: no step changes anything any more
};

BodyPhysics::BodyPhysics(const MapSpec& spec, std::shared_ptr<const StaticPhysicsShapes> statics,
                         const std::vector<MoverSpec>& movers, bool push)
    : impl_(std::make_unique<Impl>(spec, std::move(statics), movers, push)) {}

BodyPhysics::~BodyPhysics() = default;

void BodyPhysics::step(double t_next, double h) { impl_->step(t_next, h); }

Pose BodyPhysics::pose(std::size_t mover) const { return pose_of(impl_->movers_[mover].body->getWorldTransform()); }

Vec3 BodyPhysics::velocity(std::size_t mover) const {
  const Impl::Mover& m = impl_->movers_[mover];
  return m.spec->kinematic() ? Vec3::Zero() : vec(m.body->getLinearVelocity());
}

int BodyPhysics::add_agent(double radius, const Vec3& at, double reach) {
  assert(impl_->push);
  Impl::Agent a;
  const btTransform where(btQuaternion::getIdentity(), bt(at));
  a.shape = std::make_unique<btSphereShape>(radius);
  a.state = std::make_unique<btDefaultMotionState>(where);
  btRigidBody::btRigidBodyConstructionInfo info(0.0, a.state.get(), a.shape.get());
  info.m_friction = 0.0;     // pushes without dragging: the contact's friction is 0
  info.m_restitution = 1.0;  // the contact's restitution is the body's own
  a.body = std::make_unique<btRigidBody>(info);
  a.body->setCollisionFlags(a.body->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
  a.body->setActivationState(DISABLE_DEACTIVATION);
  a.body->setUserIndex(-2);
  impl_->world.addRigidBody(a.body.get(), kAgentGroup, kPushableGroup);
  a.sensor_shape = std::make_unique<btSphereShape>(radius + reach);
  a.sensor = std::make_unique<btPairCachingGhostObject>();
  a.sensor->setCollisionShape(a.sensor_shape.get());
  a.sensor->setWorldTransform(where);
  a.sensor->setCollisionFlags(a.sensor->getCollisionFlags() | btCollisionObject::CF_NO_CONTACT_RESPONSE);
  a.sensor->setActivationState(DISABLE_DEACTIVATION);
  a.sensor->setUserIndex(-2);
  impl_->world.addCollisionObject(a.sensor.get(), kSensorGroup, kPushableGroup | kSolidGroup);
  impl_->agents.push_back(std::move(a));
  return static_cast<int>(impl_->agents.size()) - 1;
}

void BodyPhysics::move_agent(int i, const Vec3& at) {
  Impl::Agent& a = impl_->agents[std::size_t(i)];
  const btTransform where(btQuaternion::getIdentity(), bt(at));
  a.state->setWorldTransform(where);
  a.sensor->setWorldTransform(where);
}

void BodyPhysics::remove_agent(int i) {
  Impl::Agent& a = impl_->agents[std::size_t(i)];
  if (!a.in_world) return;
  impl_->world.removeRigidBody(a.body.get());
  impl_->world.removeCollisionObject(a.sensor.get());
  a.in_world = false;
}

int BodyPhysics::bodies_near_agent(int i, std::span<int> out) const {
  const Impl::Agent& a = impl_->agents[std::size_t(i)];
  if (!a.in_world) return 0;
  const int n = a.sensor->getNumOverlappingObjects();
  if (n > static_cast<int>(out.size())) return n;
  for (int k = 0; k < n; ++k) out[std::size_t(k)] = a.sensor->getOverlappingObject(k)->getUserIndex();
  std::sort(out.begin(), out.begin() + n);
  return n;
}

void BodyPhysics::bodies_in(const Box& box, std::vector<int>& out) const {
  struct Collect : btBroadphaseAabbCallback {
    std::vector<int>* out;
    const std::vector<Impl::Mover>* movers;
    bool process(const btBroadphaseProxy* proxy) override {
      const auto* object = static_cast<const btCollisionObject*>(proxy->m_clientObject);
      const int m = object->getUserIndex();
      if (m >= 0 && !(*movers)[std::size_t(m)].spec->kinematic()) out->push_back(m);
      return true;
    }
  } collect;
  collect.out = &out;
  collect.movers = &impl_->movers_;
  impl_->broadphase.aabbTest(bt(box.lo), bt(box.hi), collect);
}

}  // namespace peg3d::world
