#include "world/bodies/mover_timeline.hpp"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>

#include <fmt/format.h>

#include "geometry/angles.hpp"
#include "world/bodies/body_physics.hpp"
#include "world/map/movers.hpp"

namespace peg3d::world {
namespace {

// The rotation angle between two orientations, rad.
double angle_between(const Quat& a, const Quat& b) { return a.angularDistance(b); }

// A bound on how far any point within `radius` of the centre moves from pose a to pose b (interpolated
// between them: positions linearly, orientations spherically): the centre's step plus the arc of the
// rotation angle theta, with theta <= pi |qb -+ qa| for unit quaternions (|qb - qa| = 2 sin(theta / 4) on
// the same hemisphere, and sin x >= 2 x / pi up to pi / 2), which spares an inverse cosine a keyframe.
double point_travel(const Pose& a, const Pose& b, double radius) {
  const Eigen::Vector4d qa = a.orientation.coeffs(), qb = b.orientation.coeffs();
  const double turn = std::min((qb - qa).norm(), (qb + qa).norm());
  return (b.position - a.position).norm() + kPi * turn * radius;
}

// Two poses equal to the bit: a body Bullet put to sleep keeps its transform exactly.
bool same_bits(const Pose& a, const Pose& b) {
  return std::memcmp(a.position.data(), b.position.data(), 3 * sizeof(double)) == 0 &&
         std::memcmp(a.orientation.coeffs().data(), b.orientation.coeffs().data(), 4 * sizeof(double)) == 0;
}

// Bounds are widened by this much (m), so that rounding in building them never leaves a point of a mover out.
constexpr double kBoundsMargin = 1e-6;

// Scripted movers' bounds over a block are sampled this many times at most; between samples the speed bound
// covers the rest.
constexpr long kScriptedSamples = 8;

struct Layout {
  int stride = 1;
  long substeps = 0, keyframes = 0, block_keyframes = 1;
  std::size_t blocks = 1;
};

// `stride` substeps a keyframe at `rate_hz`.
Layout layout_of(int rate_hz, int stride, double duration) {
  Layout l;
  l.stride = stride;
  l.substeps = static_cast<long>(std::ceil(duration * rate_hz - 1e-9));
  l.keyframes = (l.substeps + l.stride - 1) / l.stride;
  const double per_s = static_cast<double>(rate_hz) / l.stride;
  l.block_keyframes = std::max(1L, std::lround(MoverTimeline::kBlockSeconds * per_s));
  l.blocks = static_cast<std::size_t>(std::max(1L, (l.keyframes + l.block_keyframes - 1) / l.block_keyframes));
  return l;
}

}  // namespace

// One block of the timeline: keyframes first..last (a block shares its end keyframes with its neighbours) of
// every dynamic body, stored once for a body at rest over the whole block, and the movers' bounds over it.
struct MoverTimeline::Block {
  long first = 0, last = 0;
  std::vector<std::uint32_t> start;   ///< per dynamic body: index in poses of its keyframe `first`
  std::vector<std::uint8_t> resting;  ///< per dynamic body: 1 when one pose holds for the whole block
  std::vector<Pose> poses;

  const Pose& at(int row, long k) const {
    return poses[start[std::size_t(row)] + (resting[std::size_t(row)] ? 0 : std::size_t(k - first))];
  }
  std::size_t bytes() const {
    return sizeof(Block) + start.capacity() * sizeof(std::uint32_t) + resting.capacity() + poses.capacity() * sizeof(Pose);
  }
};

// The Bullet world the dynamic bodies move in, advanced keyframe by keyframe as blocks are built.
class MoverTimeline::Simulation {
 public:
  Simulation(const MapSpec& spec, const std::vector<TriangleMesh>& meshes, const std::vector<MoverSpec>& movers,
             const std::vector<int>& dynamic_index, int dynamic)
      : physics_(spec, make_static_physics_shapes(spec, meshes), movers), dynamic_index_(dynamic_index), h_(1.0 / spec.physics.rate_hz), tracks_(std::size_t(dynamic)) {
    record();
  }

  /// Every dynamic body's keyframes first..last (the first one is where the last call ended), `stride` substeps
  /// apart, in tracks()[row].
  void advance(long first, long last, int stride) {
    for (auto& t : tracks_) {
      const Pose start = t.empty() ? Pose{} : t.back();
      t.clear();
      t.push_back(start);
    }
    for (long k = first; k < last; ++k) {
      for (int j = 0; j < stride; ++j, ++substep_) physics_.step((substep_ + 1) * h_, h_);
      record();
    }
  }
  const std::vector<std::vector<Pose>>& tracks() const { return tracks_; }

 private:
  void record() {
    for (std::size_t i = 0; i < dynamic_index_.size(); ++i) {
      if (dynamic_index_[i] >= 0) tracks_[std::size_t(dynamic_index_[i])].push_back(physics_.pose(i));
    }
  }

  BodyPhysics physics_;
  const std::vector<int>& dynamic_index_;
  double h_;
  long substep_ = 0;
  std::vector<std::vector<Pose>> tracks_;  ///< per dynamic body: the keyframes of the block being built
};

std::size_t MoverTimeline::estimate(long keyframes, std::size_t blocks, std::size_t dynamic, std::size_t indexed) {
  const std::size_t poses = dynamic * (std::size_t(keyframes) + blocks) * sizeof(Pose);
  // Per block: the pose offsets and rest flags, and per indexed mover its bounds in the index (floats, padding
  // and its cluster's share: under 48 bytes) and its bounds while the index is built (a Box); 72 bytes bound both.
  const std::size_t per_block = sizeof(Block) + dynamic * (sizeof(std::uint32_t) + 1) + indexed * (sizeof(Box) + 24);
  return poses + blocks * per_block;
}

std::size_t MoverTimeline::worst_case_bytes(const MapSpec& spec, double duration, int stride) {
  const Layout l = layout_of(spec.physics.rate_hz, stride, duration);
  std::size_t dynamic = 0;
  for (const MoverSpec& m : spec.movers) dynamic += !m.kinematic();
  return estimate(l.keyframes, l.blocks, dynamic, spec.movers.size());
}

std::size_t MoverTimeline::worst_case_bytes(const MapSpec& spec, double duration) {
  const std::optional<int> k = spec.physics.keyframe_hz;
  return worst_case_bytes(spec, duration, k && *k > 0 ? spec.physics.rate_hz / *k : 1);
}

MoverTimeline::Rate MoverTimeline::keyframe_rate(const MapSpec& spec, double duration, std::size_t max_bytes) {
  const int rate = spec.physics.rate_hz;
  if (const std::optional<int> k = spec.physics.keyframe_hz) return {*k > 0 ? rate / *k : 1, false};
  // Strides in increasing order are rates in decreasing order: the first that fits is the highest.
  int lowest = 1;
  for (int stride = 1; stride <= rate; ++stride) {
    if (rate % stride != 0) continue;
    if (stride > 1 && rate / stride < kMinChosenKeyframeHz) break;
    lowest = stride;
    if (worst_case_bytes(spec, duration, stride) <= max_bytes) return {stride, true};
  }
  return {lowest, true};  // fits at no rate the timeline may choose: refused by the constructor
}

MoverTimeline::MoverTimeline(const MapSpec& spec, const std::vector<TriangleMesh>& meshes, double duration,
                             std::size_t max_bytes, bool with_dynamic)
    : movers_(spec.movers), with_dynamic_(with_dynamic), rate_hz_(spec.physics.rate_hz) {
  // Chosen from the map's dynamic bodies whether or not this timeline keeps them, so that push mode's timeline
  // of the scripted movers has the layout of the shared one.
  const Rate rate = keyframe_rate(spec, duration, max_bytes);
  const Layout l = layout_of(rate_hz_, rate.stride, duration);
  stride_ = l.stride;
  keyframe_rate_chosen_ = rate.chosen;
  keyframes_per_s_ = static_cast<double>(rate_hz_) / stride_;
  keyframes_ = l.keyframes;
  block_keyframes_ = l.block_keyframes;
  duration_ = static_cast<double>(keyframes_ * stride_) * (1.0 / rate_hz_);
  dynamic_index_.assign(movers_.size(), -1);
  scripted_.reserve(movers_.size());
  for (std::size_t i = 0; i < movers_.size(); ++i) {
    scripted_.emplace_back(movers_[i]);
    if (!movers_[i].kinematic()) {
      dynamic_index_[i] = dynamic_++;
      start_poses_.push_back({movers_[i].start, orientation_deg(movers_[i].rotation_deg)});
    }
    if (with_dynamic_ || movers_[i].kinematic()) queried_.push_back(static_cast<int>(i));
    if (movers_[i].kinematic()) scripted_speed_ = std::max(scripted_speed_, scripted_speed(movers_[i]));
    reach_.push_back(movers_[i].shape.bounding_radius());
  }
  if (!with_dynamic_) {
    // Only the scripted movers' bounds are kept; nothing is simulated.
    worst_case_bytes_ = estimate(l.keyframes, l.blocks, 0, queried_.size());
    blocks_.resize(l.blocks);
    travel_.resize(l.blocks);
    windows_.resize((l.blocks + kWindowBlocks - 1) / kWindowBlocks);
    return;
  }
  worst_case_bytes_ = estimate(l.keyframes, l.blocks, std::size_t(dynamic_), movers_.size());
  every_substep_bytes_ = worst_case_bytes(spec, duration, 1);
  if (worst_case_bytes_ > max_bytes && rate.chosen) {
    throw MapError(spec.source, spec.physics.line, "physics.keyframe_hz",
                   fmt::format("{} dynamic bodies over {:g} s need up to {:.0f} MiB for their motion (every body "
                               "moving all the time) even at {:g} keyframes/s, the lowest rate chosen when the map "
                               "sets none, more than the budget of {:.0f} MiB: set a lower physics.keyframe_hz "
                               "(dividing rate_hz = {}), fewer bodies or a shorter game",
                               dynamic_, duration, worst_case_bytes_ / 1048576.0, keyframes_per_s_,
                               max_bytes / 1048576.0, rate_hz_));
  }
  if (worst_case_bytes_ > max_bytes) {
    const double per_keyframe_hz = static_cast<double>(worst_case_bytes_) / keyframes_per_s_;
    const int fits = static_cast<int>(std::floor(static_cast<double>(max_bytes) / per_keyframe_hz));
    throw MapError(spec.source, spec.physics.line, "physics.keyframe_hz",
                   fmt::format("{} dynamic bodies over {:g} s at {:g} keyframes/s need up to {:.0f} MiB for their "
                               "motion (every body moving all the time), more than the budget of {:.0f} MiB: store "
                               "fewer keyframes (physics.keyframe_hz at most about {}, dividing rate_hz = {}), fewer "
                               "bodies or a shorter game",
                               dynamic_, duration, keyframes_per_s_, worst_case_bytes_ / 1048576.0,
                               max_bytes / 1048576.0, std::max(fits, 0), rate_hz_));
  }
  blocks_.resize(l.blocks);
  travel_.resize(l.blocks);
  windows_.resize((l.blocks + kWindowBlocks - 1) / kWindowBlocks);
  if (dynamic_ > 0) simulation_ = std::make_unique<Simulation>(spec, meshes, movers_, dynamic_index_, dynamic_);
}

MoverTimeline::~MoverTimeline() = default;

std::size_t MoverTimeline::block_at(double t) const {
  const double u = std::clamp(t * rate_hz_ / stride_, 0.0, static_cast<double>(keyframes_));
  const auto b = static_cast<std::size_t>(static_cast<long>(u) / block_keyframes_);
  return std::min(b, blocks_.size() - 1);
}

const MoverTimeline::Block& MoverTimeline::block(std::size_t b) const {
  if (b >= ready_.load(std::memory_order_acquire)) simulate_through(b);
  return *blocks_[b];
}

const BoxIndex& MoverTimeline::window(std::size_t b) const {
  if (b >= ready_.load(std::memory_order_acquire)) simulate_through(b);
  return *windows_[b / kWindowBlocks];
}

void MoverTimeline::simulate_through(std::size_t b) const {
  const std::lock_guard lock(simulate_mutex_);
  const auto t0 = std::chrono::steady_clock::now();
  // Whole windows: the index of a window is built over the bounds of all its blocks.
  b = std::min(blocks_.size() - 1, (b / kWindowBlocks + 1) * kWindowBlocks - 1);
  std::vector<Box> frames;
  for (std::size_t r = ready_.load(std::memory_order_relaxed); r <= b; ++r) {
    auto block = simulate_block(r);
    const std::size_t frame = r % kWindowBlocks;
    frames.resize((frame + 1) * queried_.size());
    travel_[r] = bound_block(*block, std::span<Box>(frames).subspan(frame * queried_.size()));
    bytes_.fetch_add(block->bytes(), std::memory_order_relaxed);
    blocks_[r] = std::move(block);
    if (frame + 1 == kWindowBlocks || r + 1 == blocks_.size()) {
      auto index = std::make_unique<const BoxIndex>(frames, static_cast<int>(frame + 1));
      bytes_.fetch_add(index->bytes(), std::memory_order_relaxed);
      windows_[r / kWindowBlocks] = std::move(index);
      frames.clear();
      ready_.store(r + 1, std::memory_order_release);
    }
  }
  if (ready_.load(std::memory_order_relaxed) == blocks_.size()) simulation_.reset();  // every keyframe is stored
  simulate_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::unique_ptr<MoverTimeline::Block> MoverTimeline::simulate_block(std::size_t r) const {
  auto block = std::make_unique<Block>();
  block->first = static_cast<long>(r) * block_keyframes_;
  block->last = std::min(keyframes_, block->first + block_keyframes_);
  const long n = block->last - block->first + 1;
  // The dynamic bodies' keyframes, each body's stored once when it did not move over the whole block.
  block->start.resize(std::size_t(with_dynamic_ ? dynamic_ : 0));
  block->resting.resize(std::size_t(with_dynamic_ ? dynamic_ : 0));
  if (!simulation_) return block;
  simulation_->advance(block->first, block->last, stride_);
  std::size_t total = 0;
  for (const auto& t : simulation_->tracks()) {
    total += std::all_of(t.begin(), t.end(), [&](const Pose& p) { return same_bits(p, t.front()); }) ? 1 : std::size_t(n);
  }
  block->poses.reserve(total);
  for (int row = 0; row < dynamic_; ++row) {
    const auto& t = simulation_->tracks()[std::size_t(row)];
    const bool rests = std::all_of(t.begin(), t.end(), [&](const Pose& p) { return same_bits(p, t.front()); });
    block->start[std::size_t(row)] = static_cast<std::uint32_t>(block->poses.size());
    block->resting[std::size_t(row)] = rests ? 1 : 0;
    if (rests) {
      block->poses.push_back(t.front());
      ++resting_entries_;
    } else {
      block->poses.insert(block->poses.end(), t.begin(), t.end());
      ++moving_entries_;
    }
  }
  return block;
}

double MoverTimeline::bound_block(const Block& block, std::span<Box> bounds) const {
  double block_travel = 0.0;
  const long n = block.last - block.first + 1;
  const double t_first = static_cast<double>(block.first * stride_) / rate_hz_;
  const double t_last = static_cast<double>(block.last * stride_) / rate_hz_;
  for (std::size_t leaf = 0; leaf < queried_.size(); ++leaf) {
    const std::size_t m = std::size_t(queried_[leaf]);
    const MoverSpec& spec = movers_[m];
    Box box{Vec3::Constant(std::numeric_limits<double>::infinity()), Vec3::Constant(-std::numeric_limits<double>::infinity())};
    double widen = reach_[m] + kBoundsMargin;
    if (spec.kinematic()) {
      // Samples in time, and between two of them the centre moves at most speed * interval / 2 from the nearer.
      const long samples = std::min(kScriptedSamples, std::max(1L, n - 1));
      for (long s = 0; s <= samples; ++s) {
        const Vec3 c = scripted_[m].position(t_first + (t_last - t_first) * static_cast<double>(s) / samples);
        box.lo = box.lo.cwiseMin(c), box.hi = box.hi.cwiseMax(c);
      }
      widen += scripted_speed(spec) * 0.5 * (t_last - t_first) / samples;
    } else {
      const int row = dynamic_index_[m];
      const long kmax = block.resting[std::size_t(row)] ? block.first : block.last;
      double travel = 0.0;
      for (long k = block.first; k <= kmax; ++k) {
        const Pose& at = block.at(row, k);
        box.lo = box.lo.cwiseMin(at.position), box.hi = box.hi.cwiseMax(at.position);
        if (k > block.first) travel += point_travel(block.at(row, k - 1), at, reach_[m]);
      }
      block_travel = std::max(block_travel, travel);
    }
    box.lo.array() -= widen;
    box.hi.array() += widen;
    bounds[leaf] = box;
  }
  return block_travel;
}

const Pose& MoverTimeline::keyframe(int row, long k) const {
  const std::size_t b = std::min(static_cast<std::size_t>(k / block_keyframes_), blocks_.size() - 1);
  return block(b).at(row, k);
}

Pose MoverTimeline::pose(int m, double t) const {
  const MoverSpec& spec = movers_[std::size_t(m)];
  if (spec.kinematic()) return scripted_[std::size_t(m)].pose(t);
  const int row = dynamic_index_[std::size_t(m)];
  if (!with_dynamic_) return start_poses_[std::size_t(row)];
  if (keyframes_ == 0) return keyframe(row, 0);
  const double u = std::clamp(t * rate_hz_ / stride_, 0.0, static_cast<double>(keyframes_));
  const long k = std::min(static_cast<long>(u), keyframes_ - 1);
  const double s = u - static_cast<double>(k);
  // Keyframes k and k + 1 lie in one block: the one of k (a block ends with the first keyframe of the next).
  const Block& b = block(std::min(static_cast<std::size_t>(k / block_keyframes_), blocks_.size() - 1));
  const Pose& p0 = b.at(row, k);
  const Pose& p1 = b.at(row, k + 1);
  // A ball's orientation does not change where its points are: skip the spherical interpolation.
  if (spec.shape.kind == Shape::Kind::kSphere) return {p0.position + s * (p1.position - p0.position), p0.orientation};
  return interpolate(p0, p1, s);
}

double MoverTimeline::travel_bound(int m, double t0, double t1) const {
  const MoverSpec& spec = movers_[std::size_t(m)];
  if (spec.kinematic()) return scripted_speed(spec) * (t1 - t0);  // orientation is fixed
  if (!with_dynamic_) return 0.0;
  const int row = dynamic_index_[std::size_t(m)];
  const double r = spec.shape.bounding_radius();
  const long k0 = std::clamp(static_cast<long>(std::floor(t0 * rate_hz_ / stride_)), 0L, keyframes_);
  const long k1 = std::clamp(static_cast<long>(std::ceil(t1 * rate_hz_ / stride_)), 0L, keyframes_);
  // Any point of the body: its centre's path plus the arc its farthest point sweeps, keyframe by keyframe.
  double bound = 0.0;
  for (long k = k0; k < k1; ++k) {
    const Block& b = block(std::min(static_cast<std::size_t>(k / block_keyframes_), blocks_.size() - 1));
    const Pose& a = b.at(row, k);
    const Pose& c = b.at(row, k + 1);
    bound += (c.position - a.position).norm() + angle_between(a.orientation, c.orientation) * r;
  }
  return bound;
}

double MoverTimeline::max_travel(double t0, double t1) const {
  double travel = scripted_speed_ * (t1 - t0);
  if (with_dynamic_ && dynamic_ > 0) {
    const std::size_t last = block_at(t1);
    if (last >= ready_.load(std::memory_order_acquire)) simulate_through(last);
    for (std::size_t b = block_at(t0); b <= last; ++b) travel += travel_[b];
  }
  return travel;
}

bool MoverTimeline::clear_of_contact(double clearance, const Vec3& from, const Vec3& to, double radius, double t0,
                                     double dt) const {
  // At s of the step the sphere's centre is within |to - from| of `from` and every mover point within
  // max_travel of where it was at t0, so each gap stays above clearance - radius - both. The margin covers
  // the rounding of the distances conservative advancement computes.
  constexpr double kMargin = 1e-6;
  if (!indexed(t0, t0 + dt) || !(clearance < std::numeric_limits<double>::infinity())) return false;
  return clearance - radius - (to - from).norm() - max_travel(t0, t0 + dt) > kContactTolerance + kMargin;
}

void offer_nearer(int m, const Shape& shape, double reach, const Pose& at, const Vec3& p, MoverPoint& best) {
  // Cheap rejection on the bounding ball before the exact distance. Not ">=": an equally near mover of a lower
  // index than the best one found wins the tie, as in a visit in index order.
  if ((p - at.position).norm() - reach > best.distance) return;
  const ShapePoint s = nearest_on_shape(shape, at, p);
  if (s.distance < best.distance || (best.mover >= 0 && s.distance == best.distance && m < best.mover)) {
    best = {m, s.distance, s.point};
  }
}

TouchPoint touch_point(const Shape& shape, const Pose& at, const Vec3& c, double radius) {
  const ShapePoint sp = nearest_on_shape(shape, at, c);
  Vec3 normal = c - sp.point;
  if (normal.norm() == 0.0) normal = c - at.position;  // centre inside the shape: away from its centre
  normal = normal.norm() > 0.0 ? Vec3(normal.normalized()) : Vec3(Vec3::UnitZ());
  return {sp.distance > 0.0 ? sp.point : Vec3(c - radius * normal), normal};
}

void MoverTimeline::nearer(int m, const Vec3& p, double t, MoverPoint& best) const {
  offer_nearer(m, movers_[std::size_t(m)].shape, reach_[std::size_t(m)], pose(m, t), p, best);
}

MoverPoint MoverTimeline::nearest(const Vec3& p, double t, double cap, int hint) const {
  if (!indexed(t, t)) return nearest_scan(p, t, cap);
  MoverPoint best;
  best.distance = cap;
  // The hint first (a mover the queries look at), then every other one the index does not rule out: each mover
  // is offered once, and offer_nearer's answer does not depend on the order.
  if (hint >= 0 && hint < count() && (with_dynamic_ || movers_[std::size_t(hint)].kinematic())) nearer(hint, p, t, best);
  const std::size_t b = block_at(t);
  window(b).nearest(static_cast<int>(b % kWindowBlocks), p, best.distance, [&](int leaf) {
    const int m = queried_[std::size_t(leaf)];
    if (m != hint) nearer(m, p, t, best);
    return best.distance;
  });
  return best;
}

namespace {

// Mover m as the answer of a ray query when the ray meets it nearer (the lower index at one distance). A ray
// that passes the shape's bounding ball (radius `reach`) by, or enters it beyond the best distance, cannot meet
// the shape nearer: the ball, widened far above the rounding of its entry, spares the exact test's rotation
// and divisions for most candidates of a scan (68 a scan on quarry's movers, 8 of them hits).
void offer_hit(int m, const Shape& shape, double reach, const Pose& at, const Ray& ray, MoverHit& best) {
  if (ray_sphere_entry(ray, at.position, reach * (1.0 + 1e-9) + 1e-9) > best.distance) return;
  const auto t = ray_shape(ray, shape, at, best.distance);
  if (t && (*t < best.distance || (*t == best.distance && (best.mover < 0 || m < best.mover)))) best = {m, *t};
}

}  // namespace

MoverHit MoverTimeline::first_along(const Ray& ray, double t, double range) const {
  if (!indexed(t, t)) return first_along_scan(ray, t, range);
  MoverHit best{-1, range};
  const std::size_t b = block_at(t);
  window(b).along(static_cast<int>(b % kWindowBlocks), ray.origin, ray.direction, range, [&](int leaf) {
    const int m = queried_[std::size_t(leaf)];
    offer_hit(m, movers_[std::size_t(m)].shape, reach_[std::size_t(m)], pose(m, t), ray, best);
    return best.distance;
  });
  return best;
}

void MoverTimeline::first_along_fan(const Vec3& origin, std::span<const Vec3> directions, double t,
                                    std::span<MoverHit> best) const {
  assert(directions.size() == best.size() && directions.size() <= std::size_t(BoxIndex::kFanRays));
  if (!indexed(t, t)) {
    for (std::size_t k = 0; k < best.size(); ++k) best[k] = first_along_scan({origin, directions[k]}, t, best[k].distance);
    return;
  }
  double bounds[BoxIndex::kFanRays];
  for (std::size_t k = 0; k < best.size(); ++k) bounds[k] = best[k].distance;
  const std::size_t b = block_at(t);
  window(b).fan(static_cast<int>(b % kWindowBlocks), origin, directions, bounds, [&](int leaf, std::uint64_t rays) {
    const int m = queried_[std::size_t(leaf)];
    const Pose at = pose(m, t);
    for (; rays != 0; rays &= rays - 1) {
      const int k = __builtin_ctzll(rays);
      offer_hit(m, movers_[std::size_t(m)].shape, reach_[std::size_t(m)], at, {origin, directions[std::size_t(k)]}, best[std::size_t(k)]);
      bounds[k] = best[std::size_t(k)].distance;
    }
  });
}

MoverHit MoverTimeline::first_along_scan(const Ray& ray, double t, double range) const {
  MoverHit best{-1, range};
  for (const int m : queried_) offer_hit(m, movers_[std::size_t(m)].shape, reach_[std::size_t(m)], pose(m, t), ray, best);
  return best;
}

MoverPoint MoverTimeline::nearest_scan(const Vec3& p, double t, double cap) const {
  MoverPoint best;
  best.distance = cap;
  for (const int m : queried_) {
    const MoverSpec& spec = movers_[std::size_t(m)];
    const Pose at = pose(m, t);
    // Cheap rejection on the bounding ball before the exact distance.
    if ((p - at.position).norm() - spec.shape.bounding_radius() >= best.distance) continue;
    const ShapePoint s = nearest_on_shape(spec.shape, at, p);
    if (s.distance < best.distance) best = {m, s.distance, s.point};
  }
  return best;
}

MoverPoint MoverTimeline::nearest_at_start(const Vec3& p, double cap) const {
  MoverPoint best = nearest(p, 0.0, cap);
  if (with_dynamic_) return best;
  for (int m = 0; m < count(); ++m) {
    if (!movers_[std::size_t(m)].kinematic()) nearer(m, p, 0.0, best);
  }
  return best;
}

int MoverTimeline::candidates(const Box& box, double reach, double t0, double t1, std::span<int> out) const {
  if (!indexed(t0, t1)) return -1;
  const double widen = reach + kBoundsMargin;
  const Box query{box.lo.array() - widen, box.hi.array() + widen};
  std::size_t n = 0;
  bool overflow = false;
  for (std::size_t b = block_at(t0), last = block_at(t1); b <= last; ++b) {
    window(b).overlapping(static_cast<int>(b % kWindowBlocks), query, [&](int leaf) {
      if (n < out.size()) {
        out[n++] = queried_[std::size_t(leaf)];
      } else {
        overflow = true;
      }
    });
  }
  if (overflow) return static_cast<int>(out.size()) + 1;
  std::sort(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(n));
  return static_cast<int>(std::unique(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(n)) - out.begin());
}

void MoverTimeline::contact_with(int m, const Vec3& from, const Vec3& to, double radius, double t0, double dt,
                                 std::optional<Contact>& best) const {
  const MoverSpec& spec = movers_[std::size_t(m)];
  const double agent_travel = (to - from).norm();
  const double mover_travel = travel_bound(m, t0, t0 + dt);
  const double closing = agent_travel + mover_travel;  // relative travel over the whole step: a bound
  // Rejection: too far apart for the step to close the gap.
  const Pose p0 = pose(m, t0);
  if ((from - p0.position).norm() - spec.shape.bounding_radius() - radius > closing + kContactTolerance) return;
  // Conservative advancement: at s (fraction of the step) the gap g(s) can shrink by at most closing * ds, so
  // advancing by g / closing never skips a contact, however fast the two move.
  const auto found = [&](double s, const Pose& at, const Vec3& c, double signed_gap, bool gave_up) {
    const TouchPoint tp = touch_point(spec.shape, at, c, radius);
    Contact contact;
    contact.kind = ObstacleKind::kMover;
    contact.obstacle_id = m;
    contact.fraction = s;
    contact.point = tp.point;
    contact.normal = tp.normal;
    contact.penetration = s == 0.0 ? std::max(0.0, -signed_gap) : 0.0;
    contact.gave_up = gave_up;
    best = contact;
  };
  double s = 0.0;
  for (int iteration = 0; iteration < kMaxAdvancementSteps; ++iteration) {
    const Vec3 c = from + s * (to - from);
    const Pose at = pose(m, t0 + s * dt);
    const double signed_gap = signed_distance(spec.shape, at, c) - radius;
    if (signed_gap <= kContactTolerance) {
      if (!best || s < best->fraction) found(s, at, c, signed_gap, false);
      return;
    }
    if (closing <= 0.0) return;  // neither moves: the gap stays
    const double next = s + signed_gap / closing;
    if (next > 1.0) return;                         // free to the end of the step
    if (best && next >= best->fraction) return;     // cannot beat a contact already found
    if (iteration + 1 == kMaxAdvancementSteps) {
      // Out of steps before an answer: a contact where the sphere was last measured apart, never a miss.
      found(s, at, c, signed_gap, true);
      return;
    }
    s = next;
  }
}

std::optional<Contact> MoverTimeline::first_contact(const Vec3& from, const Vec3& to, double radius, double t0,
                                                         double dt) const {
  constexpr std::size_t kMaxCandidates = 256;
  int found[kMaxCandidates];
  const int n = candidates({from.cwiseMin(to), from.cwiseMax(to)}, radius + kContactTolerance, t0, t0 + dt, found);
  if (n < 0 || n > static_cast<int>(kMaxCandidates)) return first_contact_scan(from, to, radius, t0, dt);
  // In index order, as the scan: of equally early contacts the lower index wins.
  std::optional<Contact> best;
  for (int i = 0; i < n; ++i) contact_with(found[i], from, to, radius, t0, dt, best);
  return best;
}

std::optional<Contact> MoverTimeline::first_contact_scan(const Vec3& from, const Vec3& to, double radius,
                                                              double t0, double dt) const {
  std::optional<Contact> best;
  for (const int m : queried_) contact_with(m, from, to, radius, t0, dt, best);
  return best;
}

TimelineStats MoverTimeline::stats() const {
  const std::lock_guard lock(simulate_mutex_);
  TimelineStats s;
  s.dynamic_bodies = dynamic_;
  s.keyframe_hz = static_cast<int>(std::lround(keyframes_per_s_));
  s.keyframe_hz_chosen = keyframe_rate_chosen_;
  s.every_substep_bytes = every_substep_bytes_;
  s.blocks = blocks_.size();
  s.blocks_simulated = ready_.load(std::memory_order_relaxed);
  s.worst_case_bytes = worst_case_bytes_;
  s.bytes = bytes_.load(std::memory_order_relaxed);
  s.resting_entries = resting_entries_;
  s.moving_entries = moving_entries_;
  s.simulate_seconds = simulate_seconds_;
  return s;
}

}  // namespace peg3d::world
