#include "sense/image_cast.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <optional>

namespace peg3d::sense {
namespace {

// Pixels a tile's side: a tile's rays share one bounding cone, tested once against each solid's bounding ball.
constexpr int kTile = 8;

// The unit vector along v, and its length.
std::pair<Vec3, double> unit(const Vec3& v) {
  const double n = v.norm();
  return {n > 0.0 ? Vec3(v / n) : Vec3::UnitX(), n};
}

// Whether the box [lo, hi] can meet a ray of `tile` within `range` of the eye: it is not wholly outside one of the
// tile's four side planes, nor farther than the range. Conservative: it leans to yes by a hair, for rounding.
bool tile_meets_box(const ImageCastScratch::Tile& tile, const Vec3& eye, const Vec3& lo, const Vec3& hi, double range) {
  if (!tile.bounded) return (eye.cwiseMax(lo).cwiseMin(hi) - eye).squaredNorm() <= range * range;
  for (const Vec3& n : tile.planes) {
    // The box's corner farthest along the plane's inward normal.
    const Vec3 far(n.x() >= 0 ? hi.x() : lo.x(), n.y() >= 0 ? hi.y() : lo.y(), n.z() >= 0 ? hi.z() : lo.z());
    if (n.dot(far - eye) < -1e-9 * (1.0 + (far - eye).norm())) return false;
  }
  return (eye.cwiseMax(lo).cwiseMin(hi) - eye).squaredNorm() <= range * range;
}

// The nearest distance from the eye to the box [lo, hi] (0 inside).
double box_distance(const Vec3& eye, const Vec3& lo, const Vec3& hi) { return (eye.cwiseMax(lo).cwiseMin(hi) - eye).norm(); }

// The rays an image's tiles hold, and their side planes (ImageCastScratch::Tile), made when a solid first needs
// them.
void make_tiles(std::span<const Ray> rays, int width, ImageCastScratch& s) {
  if (s.tiles_made) return;
  s.tiles_made = true;
  s.tiles.clear();
  s.tile_rays.clear();
  const int height = int(rays.size() / std::size_t(width));
  for (int r0 = 0; r0 < height; r0 += kTile) {
    for (int c0 = 0; c0 < width; c0 += kTile) {
      ImageCastScratch::Tile tile;
      tile.first = int(s.tile_rays.size());
      Vec3 sum = Vec3::Zero();
      for (int r = r0; r < std::min(height, r0 + kTile); ++r) {
        for (int c = c0; c < std::min(width, c0 + kTile); ++c) {
          s.tile_rays.push_back(r * width + c);
          sum += rays[std::size_t(r * width + c)].direction;
        }
      }
      tile.count = int(s.tile_rays.size()) - tile.first;
      // The four planes through the eye and the tile's corner rays: a pinhole's rays of the tile lie between them.
      const int r1 = std::min(height, r0 + kTile) - 1, c1 = std::min(width, c0 + kTile) - 1;
      const Vec3 corner[4] = {rays[std::size_t(r0 * width + c0)].direction, rays[std::size_t(r0 * width + c1)].direction,
                              rays[std::size_t(r1 * width + c1)].direction, rays[std::size_t(r1 * width + c0)].direction};
      const Vec3 mid = unit(sum).first;
      tile.bounded = true;
      for (int e = 0; e < 4; ++e) {
        Vec3 n = corner[e].cross(corner[(e + 1) % 4]);
        if (n.squaredNorm() < 1e-24) n = Vec3::Zero();  // a degenerate edge (a tile one pixel wide) bounds nothing
        if (n.dot(mid) < 0.0) n = -n;
        tile.planes[std::size_t(e)] = n;
      }
      // Every ray of the tile on the inner side of every plane, else (not a pinhole's grid) the tile is unbounded.
      for (int j = tile.first; j < tile.first + tile.count && tile.bounded; ++j) {
        const Vec3& d = rays[std::size_t(s.tile_rays[std::size_t(j)])].direction;
        for (const Vec3& n : tile.planes) tile.bounded = tile.bounded && n.dot(d) >= -1e-12;
      }
      s.tiles.push_back(tile);
    }
  }
}

// Calls try_ray(k) for every ray of the image that may meet the candidate's box: with a pinhole, the pixels whose
// centres lie within the projected bounds of the part of the box no nearer the eye's plane than the box can be met
// (a ray's point at distance t >= c.near lies at least t times the cosine of the image's widest ray in front of the
// plane); otherwise the rays of every tile the box is not outside of.
template <class Try>
void rays_near(const ImageCastScratch::Candidate& c, std::span<const Ray> rays, int width, const Pinhole* pinhole,
               double range, ImageCastScratch& s, const Try& try_ray) {
  const Vec3& eye = rays[0].origin;
  const int height = int(rays.size() / std::size_t(width));
  if (pinhole != nullptr) {
    if (c.near <= 0.0) {  // the eye in the box: every ray
      for (int k = 0; k < int(rays.size()); ++k) try_ray(k);
      return;
    }
    const Vec3 lo = c.lo - eye, hi = c.hi - eye;
    // The nearest plane in front of the eye the box is met beyond, less a hair for rounding.
    const double half_w = 0.5 * width, half_h = 0.5 * height;
    const double widest = pinhole->focal / std::sqrt(pinhole->focal * pinhole->focal + half_w * half_w + half_h * half_h);
    const double clip = c.near * widest * (1.0 - 1e-9);
    double cmin = INFINITY, cmax = -INFINITY, rmin = INFINITY, rmax = -INFINITY;
    const auto add = [&](const Vec3& v, double x) {
      const double col = pinhole->focal * v.dot(pinhole->right) / x, row = pinhole->focal * v.dot(pinhole->down) / x;
      cmin = std::min(cmin, col), cmax = std::max(cmax, col), rmin = std::min(rmin, row), rmax = std::max(rmax, row);
    };
    // The box's corners on the far side of the clipping plane, and where its edges cross it.
    Vec3 corner[8];
    double ahead[8];
    for (int k = 0; k < 8; ++k) {
      corner[k] = Vec3((k & 1) != 0 ? hi.x() : lo.x(), (k & 2) != 0 ? hi.y() : lo.y(), (k & 4) != 0 ? hi.z() : lo.z());
      ahead[k] = corner[k].dot(pinhole->forward) - clip;
      if (ahead[k] >= 0.0) add(corner[k], ahead[k] + clip);
    }
    for (int k = 0; k < 8; ++k) {
      for (int bit = 1; bit < 8; bit <<= 1) {
        const int j = k | bit;
        if (j == k || (ahead[k] >= 0.0) == (ahead[j] >= 0.0)) continue;
        const double w = ahead[k] / (ahead[k] - ahead[j]);
        add(corner[k] + w * (corner[j] - corner[k]), clip);
      }
    }
    if (!(cmin <= cmax)) return;  // wholly behind the plane: no ray meets it
    // Pixel (r, c) looks at (c + 1/2 - width/2, r + 1/2 - height/2) on the image plane; a hair of slack for rounding.
    // (Infinite bounds, from a box beside the eye, clamp to the image's edges.)
    const auto first = [](double v, double half, int n) {
      return v <= 0.5 - half ? 0 : v >= half ? n : int(std::ceil(v + half - 0.5));
    };
    const auto last = [](double v, double half, int n) {
      return v >= half - 0.5 ? n - 1 : v <= -half ? -1 : int(std::floor(v + half - 0.5));
    };
    const double slack = 1e-6;
    const int c0 = first(cmin - slack * (1.0 + std::abs(cmin)), half_w, width);
    const int c1 = last(cmax + slack * (1.0 + std::abs(cmax)), half_w, width);
    const int r0 = first(rmin - slack * (1.0 + std::abs(rmin)), half_h, height);
    const int r1 = last(rmax + slack * (1.0 + std::abs(rmax)), half_h, height);
    for (int r = r0; r <= r1; ++r) {
      for (int col = c0; col <= c1; ++col) try_ray(r * width + col);
    }
    return;
  }
  make_tiles(rays, width, s);
  for (const ImageCastScratch::Tile& tile : s.tiles) {
    if (!tile_meets_box(tile, eye, c.lo, c.hi, range)) continue;
    for (const int k : std::span<const int>(s.tile_rays).subspan(std::size_t(tile.first), std::size_t(tile.count))) try_ray(k);
  }
}

// Tests each candidate solid (its box, its distance) against the rays that may meet it, nearer solids first; a ray
// whose best so far, bound(k), is nearer than the box is not tried. test(candidate, k, bound) tries ray k within
// `bound`.
template <class Test, class Bound>
void splat(std::span<const Ray> rays, int width, const Pinhole* pinhole, std::vector<ImageCastScratch::Candidate>& candidates,
           double range, ImageCastScratch& s, const Bound& bound, const Test& test) {
  std::sort(candidates.begin(), candidates.end(),
            [](const ImageCastScratch::Candidate& a, const ImageCastScratch::Candidate& b) { return a.near < b.near; });
  for (const ImageCastScratch::Candidate& c : candidates) {
    if (c.near > range) break;
    rays_near(c, rays, width, pinhole, range, s, [&](int k) {
      const double b = bound(k);
      if (c.near <= b) test(c, k, b);
    });
  }
}

// The static solid of each ray as StaticRayScene::cast() finds it: the triangles' (Embree), then the spheres and
// cylinders near the view, tile by tile, strictly nearer than the triangle and the arena's face.
void cast_static(const StaticRayScene& scene, std::span<const Ray> rays, int width, const Pinhole* pinhole, double range,
                 std::span<RayHit> hits, ImageCastScratch& s) {
  const std::size_t n = rays.size();
  const Vec3& eye = rays[0].origin;
  scene.cast_triangles(rays, range, hits);  // the triangles' answer (kNone: none within range)
  s.faces.resize(n);
  for (std::size_t k = 0; k < n; ++k) s.faces[k] = scene.face_hit(rays[k], range);
  if (!s.shapes.empty()) {
    // A ray's bound: the nearest of its triangle, its face and the shapes so far; solid[k], the best shape.
    s.bound.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
      s.bound[k] = std::min(hits[k].target != RayTarget::kNone ? hits[k].distance : range,
                            s.faces[k].target != RayTarget::kNone ? s.faces[k].distance : range);
    }
    s.candidates.clear();
    for (std::size_t i = 0; i < s.shapes.size(); ++i) {
      ImageCastScratch::Candidate c;
      c.id = int(i);
      const Box b = scene.shape_bounds(s.shapes[i]);
      c.lo = b.lo, c.hi = b.hi;
      c.near = box_distance(eye, c.lo, c.hi);
      s.candidates.push_back(c);
    }
    // Among shapes met at one distance, spheres before cylinders and lower indices first: s.shapes' order.
    splat(rays, width, pinhole, s.candidates, range, s, [&s](int k) { return s.bound[std::size_t(k)]; },
          [&](const ImageCastScratch::Candidate& c, int k, double bound) {
            const StaticRayScene::ShapeRef& ref = s.shapes[std::size_t(c.id)];
            const std::optional<double> d = scene.shape_hit(ref, rays[std::size_t(k)], bound);
            if (!d) return;
            RayHit& h = s.solid[std::size_t(k)];
            const bool first = h.target == RayTarget::kNone || *d < h.distance ||
                               (*d == h.distance && c.id < s.solid_id[std::size_t(k)]);
            if (!first) return;
            h = {*d, ref.kind, ref.index};
            s.solid_id[std::size_t(k)] = c.id;
            s.bound[std::size_t(k)] = std::min(s.bound[std::size_t(k)], *d);
          });
    for (std::size_t k = 0; k < n; ++k) {
      const RayHit& shape = s.solid[k];
      if (shape.target != RayTarget::kNone && (hits[k].target == RayTarget::kNone || shape.distance < hits[k].distance)) {
        hits[k] = shape;
      }
    }
  }
  // The arena's faces hold unless a solid is strictly nearer (StaticRayScene::cast's rule, to the letter).
  for (std::size_t k = 0; k < n; ++k) {
    const RayHit& face = s.faces[k];
    hits[k] = hits[k].target != RayTarget::kNone && hits[k].distance < face.distance ? hits[k] : face;
  }
}

// The timeline's movers strictly nearer than each ray's static hit, nearer movers first, tile by tile: the lowest
// index among movers met at one distance.
void cast_movers(const world::MoverTimeline& movers, double t, std::span<const Ray> rays, int width, const Pinhole* pinhole,
                 double range, std::span<RayHit> hits, ImageCastScratch& s) {
  const Vec3& eye = rays[0].origin;
  int count = movers.candidates(s.frustum, 0.0, t, t, s.movers);
  const bool all = count < 0 || std::size_t(count) > s.movers.size();
  if (all) count = movers.count();
  s.candidates.clear();
  s.poses.resize(std::size_t(movers.count()));
  for (int i = 0; i < count; ++i) {
    const int m = all ? i : s.movers[std::size_t(i)];
    const world::MoverSpec& spec = movers.mover(m);
    if (all && !movers.with_dynamic() && !spec.kinematic()) continue;  // not in the timeline's queries
    const Pose pose = movers.pose(m, t);
    s.poses[std::size_t(m)] = pose;
    const double radius = spec.shape.bounding_radius();
    ImageCastScratch::Candidate c;
    c.id = m;
    c.lo = pose.position - Vec3::Constant(radius), c.hi = pose.position + Vec3::Constant(radius);
    c.near = box_distance(eye, c.lo, c.hi);
    s.candidates.push_back(c);
  }
  splat(rays, width, pinhole, s.candidates, range, s, [&hits](int k) { return hits[std::size_t(k)].distance; },
        [&](const ImageCastScratch::Candidate& c, int k, double bound) {
          const auto d = ray_shape(rays[std::size_t(k)], movers.mover(c.id).shape, s.poses[std::size_t(c.id)], bound);
          RayHit& h = hits[std::size_t(k)];
          if (!d || !(*d < h.distance || (*d == h.distance && h.target == RayTarget::kMover && c.id < h.index))) return;
          h = {*d, RayTarget::kMover, c.id};
        });
}

}  // namespace

void cast_image(const WorldAtInstant& world, std::span<const Ray> rays, int width, const Pinhole* pinhole, double range,
                int skip, std::span<RayHit> hits, ImageCastScratch& s) {
  assert(width > 0 && rays.size() % std::size_t(width) == 0 && hits.size() == rays.size());
  const std::size_t n = rays.size();
  if (n == 0) return;
  if (world.scene->has_triangles() && !world.scene->casts_triangles_alone()) {  // an Embree without ray masks
    cast_all(world, rays, range, skip, hits);
    return;
  }
  const Vec3& eye = rays[0].origin;
  // The frustum's box: every ray's segment within range; tiles only when a solid needs them.
  s.tiles_made = false;
  s.frustum = {eye, eye};
  for (const Ray& ray : rays) {
    const Vec3 end = eye + range * ray.direction;
    s.frustum.lo = s.frustum.lo.cwiseMin(end), s.frustum.hi = s.frustum.hi.cwiseMax(end);
  }
  // The static solids: triangles through Embree, the spheres and cylinders near the frustum by where they are seen.
  world.scene->shapes_overlapping(s.frustum, s.shapes);
  s.solid.assign(n, RayHit{range, RayTarget::kNone, -1});
  s.solid_id.assign(n, -1);
  cast_static(*world.scene, rays, width, pinhole, range, hits, s);
  if (world.movers != nullptr && world.movers->count() > 0) {
    if (s.movers.size() < std::size_t(world.movers->count())) s.movers.resize(std::size_t(world.movers->count()));
    cast_movers(*world.movers, world.time, rays, width, pinhole, range, hits, s);
  }
  cast_bodies_and_balls(world, rays, skip, hits);
}

}  // namespace peg3d::sense
