#pragma once
// What an image's rays meet (the depth camera's, sense/depth_camera.hpp): rays from one eye through a pinhole's
// pixels, row-major, cast against everything sense::cast_all casts against, with its answers, faster for their
// coherence. The terrain's triangles go through Embree eight rays at a time; every other solid (the map's spheres and
// cylinders near the view, the timeline's movers near it at that instant) is tested, exactly in double precision,
// nearer ones first, by the pixels its bounding box may be seen in (as a rasteriser finds them), a pixel that already
// met something nearer than the box not at all, instead of through a hierarchy a ray at a time.

#include <array>
#include <span>
#include <vector>

#include "sense/world_rays.hpp"

namespace peg3d::sense {

/// Per-run scratch of cast_image (sized by its first call, reused after).
struct ImageCastScratch {
  struct Tile {
    int first = 0, count = 0;  ///< its rays are tile_rays[first, first + count)
    /// The inward normals of the four planes through the eye and its corner rays, which hold every ray of the tile
    /// (bounded: false when they do not, and every solid within range is then tested)
    std::array<Vec3, 4> planes;
    bool bounded = false;
  };
  /// A solid that may be in view: its box, its nearest distance from the eye, and who it is.
  struct Candidate {
    Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();
    double near = 0.0;
    int id = 0;
  };
  std::vector<Tile> tiles;
  std::vector<int> tile_rays;
  bool tiles_made = false;
  Box frustum;  ///< the box of every ray's segment within range
  std::vector<StaticRayScene::ShapeRef> shapes;
  std::vector<RayHit> solid, faces;
  std::vector<int> solid_id;
  std::vector<double> bound;
  std::vector<Candidate> candidates;
  std::vector<int> movers;
  std::vector<Pose> poses;
};

/// The pinhole that made an image's rays (unit vectors, world frame): the ray of pixel (row r, column c) runs from the
/// eye along focal forward + (c + 1/2 - width/2) right + (r + 1/2 - height/2) down, focal in pixels.
struct Pinhole {
  Vec3 forward = Vec3::UnitX(), right = -Vec3::UnitY(), down = -Vec3::UnitZ();
  double focal = 1.0;
};

/// cast_all(world, rays, range, skip, hits) for the rays of an image `width` pixels wide (rays.size() a multiple of
/// it), row-major, which share their origin. With their `pinhole`, a solid wholly in front of the eye is tried only
/// by the pixels within its box's projection; without it (or for a solid about the eye's plane), by the 8 x 8 tiles
/// it is not outside of. The same answers but where two solids lie at one distance in float but not in
/// double (a triangle and a sphere, say: cast_all's Embree decides in float there; tests/sense/image_cast_test.cpp
/// counts how rare). No allocation once `scratch` has seen an image as large.
void cast_image(const WorldAtInstant& world, std::span<const Ray> rays, int width, const Pinhole* pinhole, double range,
                int skip, std::span<RayHit> hits, ImageCastScratch& scratch);

}  // namespace peg3d::sense
