#include "world/collision/collision_world.hpp"

#include <algorithm>
#include <cassert>
#include <vector>

#include <btBulletCollisionCommon.h>

#include "core/validation.hpp"
#include "world/terrain_shapes.hpp"

namespace peg3d::world {
namespace {

// Agents are kinematic objects that stay out of the broadphase: every agent query is an explicit contactTest
// or convexSweepTest against the static obstacles. (Bullet's default filters would never pair a kinematic
// body with a static one; and keeping agents' broadphase proxies current would only fill the pair cache,
// which these queries do not read, allocating as agents roam.) The queries carry their own filter: they
// accept obstacles (StaticFilter) and reject agents.
constexpr int kAgentGroup = 1 << 6;
constexpr int kObstacleGroup = btBroadphaseProxy::StaticFilter;

// After a hit the agent is set back this far along its path, so it ends outside the obstacle even when
// Bullet's conservative advancement (which stops within 1 mm of contact) overshoots on a curved surface.
constexpr double kBackoff = 1e-3;  // m

constexpr double kCylinderMargin = 0.005;  // m

btVector3 bt(const Vec3& v) { return {v.x(), v.y(), v.z()}; }
Vec3 vec(const btVector3& v) { return {v.x(), v.y(), v.z()}; }

/// Closest swept hit against obstacles only; remembers the triangle of a mesh hit.
struct SweepCallback : btCollisionWorld::ClosestConvexResultCallback {
  int triangle = -1;
  SweepCallback(const btVector3& from, const btVector3& to) : ClosestConvexResultCallback(from, to) {
    m_collisionFilterGroup = kAgentGroup;
    m_collisionFilterMask = kObstacleGroup;
  }
  btScalar addSingleResult(btCollisionWorld::LocalConvexResult& r, bool normal_in_world) override {
    triangle = r.m_localShapeInfo != nullptr ? r.m_localShapeInfo->m_triangleIndex : -1;
    return ClosestConvexResultCallback::addSingleResult(r, normal_in_world);
  }
};

/// Deepest penetrating contact of one agent with obstacles.
struct OverlapCallback : btCollisionWorld::ContactResultCallback {
  const btCollisionObject* agent;
  double depth = 0.0;  // most negative distance seen
  const btCollisionObject* obstacle = nullptr;
  int triangle = -1;
  btVector3 point{0, 0, 0}, normal{0, 0, 1};

  explicit OverlapCallback(const btCollisionObject* a) : agent(a) {
    m_collisionFilterGroup = kAgentGroup;
    m_collisionFilterMask = kObstacleGroup;
  }
  btScalar addSingleResult(btManifoldPoint& cp, const btCollisionObjectWrapper* w0, int, int index0,
                           const btCollisionObjectWrapper* w1, int, int index1) override {
    const double d = cp.getDistance();
    if (d >= depth) return 0;
    depth = d;
    // m_normalWorldOnB points from B towards A; report it from the obstacle towards the agent.
    if (w0->getCollisionObject() == agent) {
      obstacle = w1->getCollisionObject();
      triangle = index1;
      point = cp.getPositionWorldOnB();
      normal = cp.m_normalWorldOnB;
    } else {
      obstacle = w0->getCollisionObject();
      triangle = index0;
      point = cp.getPositionWorldOnA();
      normal = -cp.m_normalWorldOnB;
    }
    return 0;
  }
};

/// Every obstacle contact of a probe sphere about a query point, the nearest ones kept in a caller's buffer.
struct NearCallback : btCollisionWorld::ContactResultCallback {
  const btCollisionObject* probe;
  double range;
  std::span<NearPoint> out;
  int count = 0;

  NearCallback(const btCollisionObject* p, double r, std::span<NearPoint> o) : probe(p), range(r), out(o) {
    m_collisionFilterGroup = kAgentGroup;
    m_collisionFilterMask = kObstacleGroup;
  }
  btScalar addSingleResult(btManifoldPoint& cp, const btCollisionObjectWrapper* w0, int, int index0,
                           const btCollisionObjectWrapper* w1, int, int index1) override {
    if (!(cp.getDistance() < 0.0)) return 0;  // beyond the range (Bullet reports near misses too)
    const bool probe_is_a = w0->getCollisionObject() == probe;
    const btCollisionObject* obstacle = probe_is_a ? w1->getCollisionObject() : w0->getCollisionObject();
    NearPoint n;
    // The probe's radius is the range, so its contact distance is the centre's distance less the range.
    n.distance = std::max(range + cp.getDistance(), 0.0);
    n.point = vec(probe_is_a ? cp.getPositionWorldOnB() : cp.getPositionWorldOnA());
    n.kind = static_cast<ObstacleKind>(obstacle->getUserIndex());
    n.obstacle_id = obstacle->getUserIndex2();
    n.triangle = n.kind == ObstacleKind::kMesh ? (probe_is_a ? index1 : index0) : -1;
    insert(n);
    return 0;
  }
  // Sorted insertion into the nearest out.size(); the order is total, so it does not depend on Bullet's.
  void insert(const NearPoint& n) {
    auto before = [](const NearPoint& a, const NearPoint& b) {
      if (a.distance != b.distance) return a.distance < b.distance;
      if (a.kind != b.kind) return a.kind < b.kind;
      if (a.obstacle_id != b.obstacle_id) return a.obstacle_id < b.obstacle_id;
      return a.triangle < b.triangle;
    };
    const int capacity = static_cast<int>(out.size());
    if (capacity == 0 || (count == capacity && !before(n, out[std::size_t(capacity - 1)]))) return;
    int i = count < capacity ? count++ : capacity - 1;
    for (; i > 0 && before(n, out[std::size_t(i - 1)]); --i) out[std::size_t(i)] = out[std::size_t(i - 1)];
    out[std::size_t(i)] = n;
  }
};

}  // namespace

struct CollisionWorld::Impl {
  struct Agent {
    std::unique_ptr<btSphereShape> shape;
    std::unique_ptr<btCollisionObject> body;
    Vec3 position = Vec3::Zero();
    double radius = 0.0;
    bool synced = false;  // the body's transform matches position
  };

  std::shared_ptr<const Arena> arena;
  CollisionOptions options;
  // Bullet's default pools hold 4096 manifolds and 4096 collision algorithms, about 7 MB per world: a batch of
  // thousands of runs (env/batch.hpp) would hold gigabytes. The queries here need a few of each at a time
  // (a pool only bounds allocation, never an answer).
  static btDefaultCollisionConstructionInfo small_pools() {
    btDefaultCollisionConstructionInfo info;
    info.m_defaultMaxPersistentManifoldPoolSize = 64;
    info.m_defaultMaxCollisionAlgorithmPoolSize = 64;
    return info;
  }
  btDefaultCollisionConfiguration configuration{small_pools()};
  btCollisionDispatcher dispatcher{&configuration};
  btDbvtBroadphase broadphase;
  btCollisionWorld world{&dispatcher, &broadphase, &configuration};
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::shared_ptr<const TerrainShapes> terrain;  // the Arena's, shared
  std::vector<std::unique_ptr<btCollisionObject>> obstacles;
  std::vector<Agent> agents;
  // obstacles_near's probe: a sphere whose radius is the range, outside the broadphase like the agents.
  btSphereShape probe_shape{1.0};
  btCollisionObject probe;
  long long sweeps = 0;

  Impl(std::shared_ptr<const Arena> a, const CollisionOptions& o)
      : arena(std::move(a)), options(o), terrain(arena->terrain_shapes()) {
    // Static obstacles never move: do not refresh their AABBs on every query.
    world.setForceUpdateAllAabbs(false);
    // Nothing here reads the broadphase's pair cache (every query is explicit), so inserting an obstacle need
    // not look for the ones it overlaps: without this, n obstacles that overlap each other cost n^2 to add
    // (60 000 copies of one sphere took 100 s).
    broadphase.m_deferedcollide = true;
    probe.setCollisionShape(&probe_shape);
    probe.setCollisionFlags(btCollisionObject::CF_KINEMATIC_OBJECT);
    probe.setUserIndex(-1);
    const MapSpec& spec = arena->map();
    for (std::size_t i = 0; i < spec.spheres.size(); ++i) {
      const SphereObstacle& s = spec.spheres[i];
      add_obstacle(std::make_unique<btSphereShape>(s.radius), s.center, ObstacleKind::kSphere, int(i));
    }
    for (std::size_t i = 0; i < spec.cylinders.size(); ++i) {
      const CylinderObstacle& c = spec.cylinders[i];
      auto shape = std::make_unique<btCylinderShapeZ>(btVector3(c.radius, c.radius, 0.5 * c.height));
      // Bullet rounds a cylinder's edges by its margin (0.04 m by default), and a margin above half the height
      // breaks a thin disc: keep it to a few millimetres and well inside the shape.
      shape->setMargin(std::min(kCylinderMargin, 0.25 * std::min(c.radius, 0.5 * c.height)));
      add_obstacle(std::move(shape), c.base + Vec3(0, 0, 0.5 * c.height), ObstacleKind::kCylinder, int(i));
    }
    for (std::size_t i = 0; i < terrain->shapes.size(); ++i) {
      // Shared with every other world over this Arena; queries only read it.
      add_obstacle(terrain->shapes[i].get(), Vec3::Zero(), ObstacleKind::kMesh, int(i));
    }
  }

  ~Impl() {
    // btCollisionWorld's destructor touches its objects' proxies: take them out while they still exist.
    for (auto& o : obstacles) world.removeCollisionObject(o.get());
  }

  void add_obstacle(std::unique_ptr<btCollisionShape> shape, const Vec3& at, ObstacleKind kind, int id) {
    add_obstacle(static_cast<const btCollisionShape*>(shape.get()), at, kind, id);
    shapes.push_back(std::move(shape));
  }

  void add_obstacle(const btCollisionShape* shape, const Vec3& at, ObstacleKind kind, int id) {
    auto object = std::make_unique<btCollisionObject>();
    // Bullet's API takes a mutable shape; a static object's shape is only read.
    object->setCollisionShape(const_cast<btCollisionShape*>(shape));
    object->setWorldTransform(btTransform(btQuaternion::getIdentity(), bt(at)));
    object->setCollisionFlags(btCollisionObject::CF_STATIC_OBJECT);
    object->setUserIndex(static_cast<int>(kind));
    object->setUserIndex2(id);
    world.addCollisionObject(object.get(), kObstacleGroup, kAgentGroup);
    obstacles.push_back(std::move(object));
  }

  void sync(Agent& a) {
    if (a.synced) return;
    a.body->setWorldTransform(btTransform(btQuaternion::getIdentity(), bt(a.position)));
    a.synced = true;
  }

  std::optional<Contact> overlap(int id) {
    Agent& a = agents[std::size_t(id)];
    sync(a);
    OverlapCallback cb(a.body.get());
    world.contactTest(a.body.get(), cb);
    if (cb.obstacle == nullptr) return std::nullopt;
    Contact c;
    c.agent = id;
    c.kind = static_cast<ObstacleKind>(cb.obstacle->getUserIndex());
    c.obstacle_id = cb.obstacle->getUserIndex2();
    c.triangle = c.kind == ObstacleKind::kMesh ? cb.triangle : -1;
    c.fraction = 0.0;
    c.point = vec(cb.point);
    c.normal = vec(cb.normal.normalized());
    c.penetration = -cb.depth;
    return c;
  }

  int near(const Vec3& p, double range, std::span<NearPoint> out) {
    probe_shape.setUnscaledRadius(range);
    probe.setWorldTransform(btTransform(btQuaternion::getIdentity(), bt(p)));
    NearCallback cb(&probe, range, out);
    world.contactTest(&probe, cb);
    return cb.count;
  }

  std::optional<Contact> move(int id, const Vec3& to) {
    Agent& a = agents[std::size_t(id)];
    const Vec3 from = a.position;
    const Vec3 delta = to - from;
    const double length = delta.norm();
    if (length == 0.0) return std::nullopt;
    if (options.distance_early_out && arena->clearance_lower_bound(from) > length + a.radius) {
      a.position = to;
      a.synced = false;
      return std::nullopt;
    }
    ++sweeps;
    const btTransform start(btQuaternion::getIdentity(), bt(from));
    const btTransform end(btQuaternion::getIdentity(), bt(to));
    SweepCallback cb(start.getOrigin(), end.getOrigin());
    world.convexSweepTest(a.shape.get(), start, end, cb, /*allowedCcdPenetration=*/0.0);
    if (!cb.hasHit()) {
      a.position = to;
      a.synced = false;
      return std::nullopt;
    }
    Contact c;
    c.agent = id;
    c.kind = static_cast<ObstacleKind>(cb.m_hitCollisionObject->getUserIndex());
    c.obstacle_id = cb.m_hitCollisionObject->getUserIndex2();
    c.triangle = c.kind == ObstacleKind::kMesh ? cb.triangle : -1;
    c.fraction = cb.m_closestHitFraction;
    c.point = vec(cb.m_hitPointWorld);
    c.normal = vec(cb.m_hitNormalWorld.normalized());
    a.position = from + std::max(0.0, c.fraction - kBackoff / length) * delta;
    a.synced = false;
    if (c.fraction == 0.0) {
      // Stopped where it stood: it may have started inside the obstacle (after place_agent).
      if (auto o = overlap(id)) c.penetration = o->penetration;
    }
    return c;
  }
};

CollisionWorld::CollisionWorld(std::shared_ptr<const Arena> arena, const CollisionOptions& options)
    : impl_(std::make_unique<Impl>(std::move(arena), options)) {}
CollisionWorld::~CollisionWorld() = default;
CollisionWorld::CollisionWorld(CollisionWorld&&) noexcept = default;
CollisionWorld& CollisionWorld::operator=(CollisionWorld&&) noexcept = default;

int CollisionWorld::add_agent(double radius) {
  require_positive("agent radius", radius);
  Impl::Agent a;
  a.radius = radius;
  a.shape = std::make_unique<btSphereShape>(radius);
  a.body = std::make_unique<btCollisionObject>();
  a.body->setCollisionShape(a.shape.get());
  a.body->setCollisionFlags(btCollisionObject::CF_KINEMATIC_OBJECT);
  a.body->setActivationState(DISABLE_DEACTIVATION);
  a.body->setWorldTransform(btTransform::getIdentity());
  const int id = static_cast<int>(impl_->agents.size());
  a.body->setUserIndex(-1);
  a.body->setUserIndex2(id);
  a.synced = true;
  impl_->agents.push_back(std::move(a));
  return id;
}

void CollisionWorld::set_agent_radius(int agent, double radius) {
  assert(agent >= 0 && agent < agent_count());
  require_positive("agent radius", radius);
  auto& a = impl_->agents[std::size_t(agent)];
  if (a.radius == radius) return;
  a.radius = radius;
  a.shape->setUnscaledRadius(radius);
}

void CollisionWorld::place_agent(int agent, const Vec3& p) {
  assert(agent >= 0 && agent < agent_count());
  auto& a = impl_->agents[std::size_t(agent)];
  a.position = p;
  a.synced = false;
}

std::optional<Contact> CollisionWorld::move_agent(int agent, const Vec3& to) {
  assert(agent >= 0 && agent < agent_count());
  assert(to.allFinite());
  return impl_->move(agent, to);
}

std::optional<Contact> CollisionWorld::overlap(int agent) const {
  assert(agent >= 0 && agent < agent_count());
  return impl_->overlap(agent);
}

int CollisionWorld::obstacles_near(const Vec3& p, double range, std::span<NearPoint> out) {
  assert(p.allFinite());
  assert(range > 0.0);
  return impl_->near(p, range, out);
}

Vec3 CollisionWorld::agent_position(int agent) const { return impl_->agents[std::size_t(agent)].position; }
int CollisionWorld::agent_count() const { return static_cast<int>(impl_->agents.size()); }
const Arena& CollisionWorld::arena() const { return *impl_->arena; }
long long CollisionWorld::sweep_count() const { return impl_->sweeps; }

}  // namespace peg3d::world
