#pragma once
// What a range sensor's rays meet among the map's static solids (issue 38): the terrain's triangles, the
// spheres and cylinders, and the arena's faces the map makes obstacles. Built once per Arena and read by every
// run at once (casting is const and thread-safe).
//
// Embree (Debian's libembree-dev) finds the first solid along a ray: its bounding-volume hierarchy over
// triangles in single precision, and the spheres and cylinders as user geometry whose intersection is computed
// by geometry/ray.hpp in double precision from the ray as given. The distance returned is exact in double
// precision for the solid Embree chose (a triangle's is recomputed in double too); what single precision can
// change is only which solid that is, where two lie within float spacing of each other along the ray or the ray
// grazes an edge: see docs/performance.md and tests/sense/static_ray_scene_test.cpp for the bound.

#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "geometry/ray.hpp"
#include "world/arena.hpp"

namespace peg3d::sense {

/// What a ray hit.
enum class RayTarget { kNone, kTriangle, kSphere, kCylinder, kArenaFace, kMover, kBall };

struct RayHit {
  double distance = 0.0;  ///< m along the ray; the ray's range when target is kNone
  RayTarget target = RayTarget::kNone;
  /// the sphere's, cylinder's or mover's index in the map, the triangle's mesh, the face (0..5: -x +x -y +y -z +z),
  /// the ball's index (sense/world_rays.hpp)
  int index = -1;
};

class StaticRayScene {
 public:
  /// Indexes the arena's terrain triangles, spheres and cylinders (about 1 s for a million triangles).
  explicit StaticRayScene(const world::Arena& arena);
  ~StaticRayScene();
  StaticRayScene(const StaticRayScene&) = delete;
  StaticRayScene& operator=(const StaticRayScene&) = delete;

  /// The first static solid along the ray within `range` (m, > 0).
  RayHit cast(const Ray& ray, double range) const;
  /// cast() for each ray, into `hits` (the same length), to the bit; in a scene without terrain eight rays at a
  /// time through Embree's packets (fastest when they share an origin, as a scan's rays do).
  void cast(std::span<const Ray> rays, double range, std::span<RayHit> hits) const;

  // The parts cast() combines, for casters that find some solids their own way (sense/image_cast.hpp): cast()'s
  // answer is the face_hit() unless the solid the triangles and the shapes give is strictly nearer, that solid the
  // nearer of cast_triangles()'s and the shapes' (ray_sphere, ray_upright_cylinder within range; spheres before
  // cylinders, lower indices first among equally near ones).

  const world::Arena& arena() const;
  /// Where the ray leaves the arena through a face the map makes an obstacle, within `range`; kNone otherwise.
  RayHit face_hit(const Ray& ray, double range) const;
  /// Whether the terrain has any triangle.
  bool has_triangles() const;
  /// Whether cast_triangles() may be called: Embree honours ray masks, so that the triangles are cast alone.
  bool casts_triangles_alone() const;
  /// The first terrain triangle along each ray within `range` (kNone beyond), as cast() finds it among the
  /// triangles alone (Embree in float, the chosen triangle's distance again in double); rays that share their
  /// origin go through Embree eight at a time.
  void cast_triangles(std::span<const Ray> rays, double range, std::span<RayHit> hits) const;
  /// A static sphere or cylinder of the map (RayTarget::kSphere or kCylinder, and its index there).
  struct ShapeRef {
    RayTarget kind = RayTarget::kSphere;
    int index = 0;
  };
  /// Writes to `out` (cleared first) the spheres and cylinders whose bounds meet `box`, spheres first, each kind by
  /// index. No allocation once `out` has held as many.
  void shapes_overlapping(const Box& box, std::vector<ShapeRef>& out) const;
  /// The box around a shape.
  Box shape_bounds(const ShapeRef& shape) const;
  /// Where the ray first meets the shape within `range`, exactly in double precision, as cast() meets it.
  std::optional<double> shape_hit(const ShapeRef& shape, const Ray& ray, double range) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The first static solid along the ray by testing every one of them in double precision: the reference the
/// tests hold StaticRayScene to, and the answer for scenes too small to index.
RayHit cast_every_solid(const world::Arena& arena, const Ray& ray, double range);

}  // namespace peg3d::sense
