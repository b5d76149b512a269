#include "sense/static_ray_scene.hpp"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

#include "geometry/box_index.hpp"

namespace peg3d::sense {
namespace {

// The arena's face the ray leaves through, when the map makes it an obstacle and it lies within range.
RayHit arena_face_hit(const world::MapSpec& map, const Ray& ray, double range) {
  const BoxExit exit = ray_box_exit(ray, map.bounds.lo, map.bounds.hi);
  const bool obstacle = exit.face == 4 ? map.floor_is_obstacle : exit.face == 5 ? map.ceiling_is_obstacle : map.walls_is_obstacle;
  if (!obstacle || exit.distance > range) return {range, RayTarget::kNone, -1};
  return {exit.distance, RayTarget::kArenaFace, exit.face};
}

// The box around a sphere or cylinder of the map.
Box shape_box(const world::MapSpec& map, const StaticRayScene::ShapeRef& shape) {
  switch (shape.kind) {
    case RayTarget::kSphere: {
      const auto& o = map.spheres[std::size_t(shape.index)];
      return {o.center - Vec3::Constant(o.radius), o.center + Vec3::Constant(o.radius)};
    }
    case RayTarget::kCylinder: {
      const auto& c = map.cylinders[std::size_t(shape.index)];
      return {c.base - Vec3(c.radius, c.radius, 0), c.base + Vec3(c.radius, c.radius, c.height)};
    }
    default: assert(false && "not a shape of the map"); return {};
  }
}

// The nearer of two hits (a tie keeps the first).
RayHit nearer(const RayHit& a, const RayHit& b) { return b.target != RayTarget::kNone && b.distance < a.distance ? b : a; }

// A query's context: Embree's, then the rays in double precision and, per ray, the exact distance of its best
// user-geometry hit so far (Embree keeps only its float). A lane's ray id indexes both.
struct ExactContext {
  RTCIntersectContext embree;
  const Ray* rays;
  double* exact;
  unsigned spheres_id;  // ties at one distance (a ray from inside several solids) go to spheres, then low indices
};

// Bounds of a user primitive in float, widened by a relative 1e-6 (and 1e-6 m) so that rounding never drops a
// solid a ray meets.
void store_bounds(RTCBounds* b, const Vec3& lo, const Vec3& hi) {
  const auto down = [](double v) { return static_cast<float>(v - 1e-6 * (1.0 + std::abs(v))); };
  const auto up = [](double v) { return static_cast<float>(v + 1e-6 * (1.0 + std::abs(v))); };
  b->lower_x = down(lo.x()), b->lower_y = down(lo.y()), b->lower_z = down(lo.z());
  b->upper_x = up(hi.x()), b->upper_y = up(hi.y()), b->upper_z = up(hi.z());
}

// Each valid lane's hit on one user primitive, exact: accepted when nearer than what the lane's ray holds (Embree
// asks primitives in any order). `hit(ray)` is the primitive's exact distance along the ray, infinite if it does
// not meet it (a double, not an optional: the optional's round trip through the stack stalled every lane).
template <class Hit>
void accept_lanes(const RTCIntersectFunctionNArguments* args, Hit&& hit) {
  auto* ctx = reinterpret_cast<ExactContext*>(args->context);
  RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, args->N);
  RTCHitN* best = RTCRayHitN_HitN(args->rayhit, args->N);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const unsigned id = RTCRayN_id(ray, args->N, i);
    const double t = hit(ctx->rays[id]);
    if (!(t < std::numeric_limits<double>::infinity())) continue;  // never met (or NaN, never accepted)
    float& tfar = RTCRayN_tfar(ray, args->N, i);
    double& exact = ctx->exact[id];
    unsigned& geom = RTCHitN_geomID(best, args->N, i);
    unsigned& prim = RTCHitN_primID(best, args->N, i);
    const float tf = static_cast<float>(t);
    if (tf > tfar) continue;
    if (tf == tfar && t >= exact) {
      const auto rank = [&](unsigned g, unsigned p) { return std::pair{g == ctx->spheres_id ? 0 : 1, p}; };
      if (t > exact || rank(args->geomID, args->primID) >= rank(geom, prim)) continue;
    }
    tfar = tf;
    exact = t;
    geom = args->geomID;
    prim = args->primID;
    RTCHitN_instID(best, args->N, i, 0) = RTC_INVALID_GEOMETRY_ID;
  }
}

void sphere_bounds(const RTCBoundsFunctionArguments* args) {
  const auto& s = static_cast<const std::vector<world::SphereObstacle>*>(args->geometryUserPtr)->at(args->primID);
  store_bounds(args->bounds_o, s.center - Vec3::Constant(s.radius), s.center + Vec3::Constant(s.radius));
}

void sphere_intersect(const RTCIntersectFunctionNArguments* args) {
  const auto& s = static_cast<const std::vector<world::SphereObstacle>*>(args->geometryUserPtr)->at(args->primID);
  accept_lanes(args, [&](const Ray& r) { return ray_sphere_entry(r, s.center, s.radius); });
}

void cylinder_bounds(const RTCBoundsFunctionArguments* args) {
  const auto& c = static_cast<const std::vector<world::CylinderObstacle>*>(args->geometryUserPtr)->at(args->primID);
  store_bounds(args->bounds_o, c.base - Vec3(c.radius, c.radius, 0), c.base + Vec3(c.radius, c.radius, c.height));
}

void cylinder_intersect(const RTCIntersectFunctionNArguments* args) {
  const auto& c = static_cast<const std::vector<world::CylinderObstacle>*>(args->geometryUserPtr)->at(args->primID);
  constexpr double kNone = std::numeric_limits<double>::infinity();
  accept_lanes(args, [&](const Ray& r) {
    // Most lanes of a packet pass the trunk by: their column test alone, inline, before the whole one.
    if (column_cut(r, c.base, c.radius).misses()) return kNone;
    return ray_upright_cylinder_entry(r, c.base, c.radius, c.height);
  });
}

}  // namespace

// Ray masks: a triangle geometry answers rays of mask kTriangleMask, the user geometry those of kShapeMask; cast()
// asks both.
constexpr unsigned kTriangleMask = 1u, kShapeMask = 2u;

// The process's one Embree device, made on first use and never released. One thread: a scene is built when the
// Arena's user asks for it, never beside the runs' threads. Never released: releasing the last device lifts
// its `threads=1` hold on TBB, which then starts a worker thread at once, and a mesh import forking
// (core/bounded_child) while that thread starts can inherit a lock it holds (seen: a sanitized test's import
// child, forked right after a scene was destroyed, blocked until the clock killed it).
namespace {
RTCDevice shared_device() {
  static const RTCDevice device = [] {
    RTCDevice d = rtcNewDevice("threads=1");
    if (d == nullptr) throw std::runtime_error("Embree: cannot create a device");
    return d;
  }();
  return device;
}
// One packet of up to eight rays, in float, lane k ray k (id k) within `range`, asking the geometries of `mask`;
// the lanes past the rays are off (valid 0).
void fill_packet(std::span<const Ray> rays, double range, unsigned mask, int* valid, RTCRayHit8& rh) {
  for (std::size_t k = 0; k < 8; ++k) {
    const bool on = k < rays.size();
    valid[k] = on ? -1 : 0;
    const Ray& ray = rays[on ? k : 0];
    rh.ray.org_x[k] = float(ray.origin.x()), rh.ray.org_y[k] = float(ray.origin.y()), rh.ray.org_z[k] = float(ray.origin.z());
    rh.ray.dir_x[k] = float(ray.direction.x()), rh.ray.dir_y[k] = float(ray.direction.y()),
    rh.ray.dir_z[k] = float(ray.direction.z());
    rh.ray.tnear[k] = 0.0f;
    rh.ray.tfar[k] = float(range);
    rh.ray.mask[k] = mask;
    rh.ray.time[k] = 0.0f;
    rh.ray.id[k] = unsigned(k);
    rh.ray.flags[k] = 0;
    rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID[k] = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
  }
}

}  // namespace

struct StaticRayScene::Impl {
  const world::Arena& arena;
  RTCScene scene = nullptr;
  unsigned spheres_id = RTC_INVALID_GEOMETRY_ID, cylinders_id = RTC_INVALID_GEOMETRY_ID;
  std::vector<unsigned> mesh_of_geometry;  // geometry ID -> mesh index (triangle geometries), else -1
  bool triangles = false;
  bool masks = false;  // the device honours ray masks (Debian's Embree does): cast_triangles can leave shapes out
  // The spheres' and cylinders' bounds (spheres first), when there are few enough to index.
  std::vector<ShapeRef> shape_of_box;
  BoxIndex shapes;

  explicit Impl(const world::Arena& a) : arena(a) {
    const RTCDevice device = shared_device();
    scene = rtcNewScene(device);
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
    rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
    const world::MapSpec& map = arena.map();
    for (std::size_t m = 0; m < arena.meshes().size(); ++m) {
      const world::TriangleMesh& mesh = arena.meshes()[m];
      if (mesh.faces.empty()) continue;
      RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
      auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                            3 * sizeof(float), mesh.vertices.size()));
      for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
        for (int k = 0; k < 3; ++k) v[3 * i + std::size_t(k)] = static_cast<float>(mesh.vertices[i][k]);
      }
      auto* f = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                               3 * sizeof(unsigned), mesh.faces.size()));
      for (std::size_t i = 0; i < mesh.faces.size(); ++i) {
        for (int k = 0; k < 3; ++k) f[3 * i + std::size_t(k)] = static_cast<unsigned>(mesh.faces[i][std::size_t(k)]);
      }
      rtcSetGeometryMask(g, kTriangleMask);
      rtcCommitGeometry(g);
      const unsigned id = rtcAttachGeometry(scene, g);
      rtcReleaseGeometry(g);
      if (mesh_of_geometry.size() <= id) mesh_of_geometry.resize(id + 1, ~0u);
      mesh_of_geometry[id] = static_cast<unsigned>(m);
      triangles = true;
    }
    const auto user = [&](unsigned count, const void* data, RTCBoundsFunction bounds, RTCIntersectFunctionN hit) {
      RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
      rtcSetGeometryUserPrimitiveCount(g, count);
      rtcSetGeometryUserData(g, const_cast<void*>(data));
      rtcSetGeometryBoundsFunction(g, bounds, nullptr);
      rtcSetGeometryIntersectFunction(g, hit);
      rtcSetGeometryMask(g, kShapeMask);
      rtcCommitGeometry(g);
      const unsigned id = rtcAttachGeometry(scene, g);
      rtcReleaseGeometry(g);
      return id;
    };
    if (!map.spheres.empty()) spheres_id = user(unsigned(map.spheres.size()), &map.spheres, sphere_bounds, sphere_intersect);
    if (!map.cylinders.empty()) {
      cylinders_id = user(unsigned(map.cylinders.size()), &map.cylinders, cylinder_bounds, cylinder_intersect);
    }
    rtcCommitScene(scene);
    if (rtcGetDeviceError(device) != RTC_ERROR_NONE) throw std::runtime_error("Embree: building the static scene failed");
    masks = rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_RAY_MASK_SUPPORTED) != 0;
    if (map.spheres.size() + map.cylinders.size() <= BoxIndex::kMaxBoxes) {
      for (std::size_t i = 0; i < map.spheres.size(); ++i) shape_of_box.push_back({RayTarget::kSphere, int(i)});
      for (std::size_t i = 0; i < map.cylinders.size(); ++i) shape_of_box.push_back({RayTarget::kCylinder, int(i)});
      std::vector<Box> boxes;
      for (const ShapeRef& shape : shape_of_box) boxes.push_back(shape_box(map, shape));
      if (!boxes.empty()) shapes = BoxIndex(boxes);
    }
  }

  ~Impl() {
    if (scene != nullptr) rtcReleaseScene(scene);
  }

  RayHit cast(const Ray& ray, double range) const {
    double exact = std::numeric_limits<double>::infinity();
    ExactContext ctx{{}, &ray, &exact, spheres_id};
    rtcInitIntersectContext(&ctx.embree);
    RTCRayHit rh{};
    rh.ray.org_x = float(ray.origin.x()), rh.ray.org_y = float(ray.origin.y()), rh.ray.org_z = float(ray.origin.z());
    rh.ray.dir_x = float(ray.direction.x()), rh.ray.dir_y = float(ray.direction.y()), rh.ray.dir_z = float(ray.direction.z());
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = float(range);
    rh.ray.mask = ~0u;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene, &ctx.embree, &rh);
    return resolve(ray, range, rh.hit.geomID, rh.hit.primID, rh.ray.tfar, exact);
  }

  // cast() for many rays, eight at a time through Embree's packet traversal (coherent when they share an origin,
  // as a scan's do): the same hits, the traversal shared.
  void cast_packets(std::span<const Ray> rays, double range, std::span<RayHit> hits) const {
    constexpr std::size_t kLanes = 8;
    const bool coherent =
        std::all_of(rays.begin(), rays.end(), [&](const Ray& r) { return r.origin == rays.front().origin; });
    for (std::size_t from = 0; from < rays.size(); from += kLanes) {
      const std::size_t n = std::min(kLanes, rays.size() - from);
      alignas(32) int valid[kLanes];
      alignas(32) RTCRayHit8 rh;
      fill_packet(rays.subspan(from, n), range, ~0u, valid, rh);
      double exact[kLanes];
      std::fill_n(exact, kLanes, std::numeric_limits<double>::infinity());
      ExactContext ctx{{}, rays.data() + from, exact, spheres_id};
      rtcInitIntersectContext(&ctx.embree);
      if (coherent) ctx.embree.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
      rtcIntersect8(valid, scene, &ctx.embree, &rh);
      for (std::size_t k = 0; k < n; ++k) {
        RayHit& hit = hits[from + k];
        hit = resolve(rays[from + k], range, rh.hit.geomID[k], rh.hit.primID[k], rh.ray.tfar[k], exact[k]);
        // A ray from inside several solids meets them all at 0, and the tie goes to the first by rank; a packet's
        // traversal culls what lies at the distance a lane already holds (a single ray's does not), so it may
        // never ask the others. Such a ray is cast again alone.
        if (hit.distance == 0.0 && hit.target != RayTarget::kArenaFace) hit = cast(rays[from + k], range);
      }
    }
  }

  // What a ray met, from Embree's answer (the geometry and primitive it chose, its float distance) and the exact
  // distance of the best user-geometry hit: the arena's face unless that solid is strictly nearer.
  RayHit resolve(const Ray& ray, double range, unsigned geometry, unsigned primitive, float float_distance,
                 double exact) const {
    if (geometry == RTC_INVALID_GEOMETRY_ID) return arena_face_hit(arena.map(), ray, range);
    RayHit solid;
    if (geometry == spheres_id || geometry == cylinders_id) {
      solid = {exact, geometry == spheres_id ? RayTarget::kSphere : RayTarget::kCylinder, int(primitive)};
    } else {
      solid = exact_triangle(ray, geometry, primitive, float_distance);
    }
    if (solid.distance > range) return arena_face_hit(arena.map(), ray, range);
    // A solid nearer than every obstacle face's plane is nearer than the face the ray would leave by: no need to
    // find that face (three divisions).
    if (solid.distance < face_planes_distance(ray.origin)) return solid;
    return nearer(arena_face_hit(arena.map(), ray, range), solid);
  }

  // A lower bound on the distance along any ray from `origin` to an obstacle face of the arena: the nearest such
  // face's plane, less a margin for rounding; 0 or below from outside the arena.
  double face_planes_distance(const Vec3& origin) const {
    const world::MapSpec& map = arena.map();
    const Vec3 &lo = map.bounds.lo, &hi = map.bounds.hi;
    double d = std::numeric_limits<double>::infinity();
    if (map.walls_is_obstacle) {
      d = std::min({origin.x() - lo.x(), hi.x() - origin.x(), origin.y() - lo.y(), hi.y() - origin.y()});
    }
    if (map.floor_is_obstacle) d = std::min(d, origin.z() - lo.z());
    if (map.ceiling_is_obstacle) d = std::min(d, hi.z() - origin.z());
    return d * (1.0 - 1e-9);
  }

  // The triangle Embree chose again in double precision, from the ray as given. Float may have seen the ray
  // inside it where double puts it just across an edge (a ray through an edge is outside one of its two
  // triangles about half the time): the ray then meets the triangle's plane on that edge, and the plane's
  // distance in double is the answer. Embree's float distance stands only for a ray along the plane.
  RayHit exact_triangle(const Ray& ray, unsigned geometry, unsigned primitive, float float_distance) const {
    const unsigned m = mesh_of_geometry[geometry];
    const world::TriangleMesh& mesh = arena.meshes()[m];
    const auto& f = mesh.faces[primitive];
    const Vec3& a = mesh.vertices[std::size_t(f[0])];
    const Vec3 &b = mesh.vertices[std::size_t(f[1])], &c = mesh.vertices[std::size_t(f[2])];
    if (const auto t = ray_triangle(ray, a, b, c, std::numeric_limits<double>::infinity())) {
      return {*t, RayTarget::kTriangle, int(m)};
    }
    const Vec3 normal = (b - a).cross(c - a);
    const double along = normal.dot(ray.direction);
    const double t = along != 0.0 ? normal.dot(a - ray.origin) / along : double(float_distance);
    return {t >= 0.0 ? t : double(float_distance), RayTarget::kTriangle, int(m)};
  }

  // The triangles alone, eight rays at a time (their origins may differ; each lane is its own ray).
  void cast_triangles(std::span<const Ray> rays, double range, std::span<RayHit> hits) const {
    constexpr std::size_t kLanes = 8;
    for (std::size_t from = 0; from < rays.size(); from += kLanes) {
      const std::size_t n = std::min(kLanes, rays.size() - from);
      alignas(32) int valid[kLanes];
      alignas(32) RTCRayHit8 rh;
      fill_packet(rays.subspan(from, n), range, kTriangleMask, valid, rh);
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
      rtcIntersect8(valid, scene, &context, &rh);
      for (std::size_t k = 0; k < n; ++k) {
        RayHit& out = hits[from + k];
        out = {range, RayTarget::kNone, -1};
        if (rh.hit.geomID[k] == RTC_INVALID_GEOMETRY_ID) continue;
        const RayHit t = exact_triangle(rays[from + k], rh.hit.geomID[k], rh.hit.primID[k], rh.ray.tfar[k]);
        if (t.distance <= range) out = t;
      }
    }
  }
};

StaticRayScene::StaticRayScene(const world::Arena& arena) : impl_(std::make_unique<Impl>(arena)) {}

const world::Arena& StaticRayScene::arena() const { return impl_->arena; }

RayHit StaticRayScene::face_hit(const Ray& ray, double range) const { return arena_face_hit(impl_->arena.map(), ray, range); }

bool StaticRayScene::has_triangles() const { return impl_->triangles; }

bool StaticRayScene::casts_triangles_alone() const { return impl_->masks; }

void StaticRayScene::cast_triangles(std::span<const Ray> rays, double range, std::span<RayHit> hits) const {
  assert(impl_->masks || !impl_->triangles);
  if (!impl_->triangles) {
    for (RayHit& h : hits) h = {range, RayTarget::kNone, -1};
    return;
  }
  impl_->cast_triangles(rays, range, hits);
}

void StaticRayScene::shapes_overlapping(const Box& box, std::vector<ShapeRef>& out) const {
  out.clear();
  const world::MapSpec& map = impl_->arena.map();
  if (impl_->shape_of_box.empty() && map.spheres.size() + map.cylinders.size() > 0) {
    // Too many to index: every one of them.
    for (std::size_t i = 0; i < map.spheres.size(); ++i) out.push_back({RayTarget::kSphere, int(i)});
    for (std::size_t i = 0; i < map.cylinders.size(); ++i) out.push_back({RayTarget::kCylinder, int(i)});
    return;
  }
  if (impl_->shape_of_box.empty()) return;
  impl_->shapes.overlapping(box, [&](auto b) { out.push_back(impl_->shape_of_box[std::size_t(b)]); });
  std::sort(out.begin(), out.end(), [](const ShapeRef& a, const ShapeRef& b) {
    return std::pair(int(a.kind), a.index) < std::pair(int(b.kind), b.index);  // kSphere before kCylinder
  });
}

Box StaticRayScene::shape_bounds(const ShapeRef& shape) const { return shape_box(impl_->arena.map(), shape); }

std::optional<double> StaticRayScene::shape_hit(const ShapeRef& shape, const Ray& ray, double range) const {
  const world::MapSpec& map = impl_->arena.map();
  switch (shape.kind) {
    case RayTarget::kSphere: {
      const auto& o = map.spheres[std::size_t(shape.index)];
      return ray_sphere(ray, o.center, o.radius, range);
    }
    case RayTarget::kCylinder: {
      const auto& c = map.cylinders[std::size_t(shape.index)];
      return ray_upright_cylinder(ray, c.base, c.radius, c.height, range);
    }
    default: assert(false && "not a shape of the map"); return std::nullopt;
  }
}
StaticRayScene::~StaticRayScene() = default;

RayHit StaticRayScene::cast(const Ray& ray, double range) const { return impl_->cast(ray, range); }

void StaticRayScene::cast(std::span<const Ray> rays, double range, std::span<RayHit> hits) const {
  // Packets pay only where there is no terrain: with it, Embree's packet traversal of triangles was slower than
  // one ray at a time for a scan's 120-degree fan (BM_StaticScan on valley and quarry, side by side on a loaded
  // machine: 4.2 to 4.3 us a scan ray by ray, 5.6 to 8.5 us in packets).
  if (rays.size() == 1 || impl_->triangles) {
    for (std::size_t i = 0; i < rays.size(); ++i) hits[i] = impl_->cast(rays[i], range);
    return;
  }
  impl_->cast_packets(rays, range, hits);
}

RayHit cast_every_solid(const world::Arena& arena, const Ray& ray, double range) {
  const world::MapSpec& map = arena.map();
  RayHit best = arena_face_hit(map, ray, range);
  const auto consider = [&](std::optional<double> t, RayTarget target, int index) {
    if (t && *t <= range && (best.target == RayTarget::kNone || *t < best.distance)) best = {*t, target, index};
  };
  for (std::size_t i = 0; i < map.spheres.size(); ++i) {
    consider(ray_sphere(ray, map.spheres[i].center, map.spheres[i].radius, range), RayTarget::kSphere, int(i));
  }
  for (std::size_t i = 0; i < map.cylinders.size(); ++i) {
    const auto& c = map.cylinders[i];
    consider(ray_upright_cylinder(ray, c.base, c.radius, c.height, range), RayTarget::kCylinder, int(i));
  }
  for (std::size_t m = 0; m < arena.meshes().size(); ++m) {
    const world::TriangleMesh& mesh = arena.meshes()[m];
    for (const auto& f : mesh.faces) {
      consider(ray_triangle(ray, mesh.vertices[std::size_t(f[0])], mesh.vertices[std::size_t(f[1])],
                            mesh.vertices[std::size_t(f[2])], range),
               RayTarget::kTriangle, int(m));
    }
  }
  return best;
}

}  // namespace peg3d::sense
