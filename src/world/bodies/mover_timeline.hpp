#pragma once
// Where every moving obstacle of a map is, at any time of a game. Scripted movers (paths, orbits) are exact
// functions of time. Dynamic bodies are simulated by a Bullet dynamics world (btDiscreteDynamicsWorld, double
// precision) at the map's physics rate, with the static obstacles, the terrain, the arena's faces and the
// scripted movers (kinematic bodies that push and are never pushed), and their poses are kept at the map's
// keyframe rate (physics.keyframe_hz; by default every substep, the exact simulated motion). Agents do not enter
// this simulation (push mode gives each run a world of its own: world/bodies/push_world.hpp), so the motion of every
// mover depends on the map alone, is computed once per map and shared read-only by all runs and threads, and
// every run sees the same physical world from the same start.
//
// Memory is bounded and known before anything is simulated. The timeline is kept in blocks of a quarter of a
// second; in a block, a body at rest (Bullet put it to sleep, so its pose stays the same to the bit) is stored
// once, a moving body at every keyframe. The budget (kMaxBytes) is checked against the worst case, every body
// moving all the time, and a map over it is refused with a MapError naming physics.keyframe_hz. Blocks are
// simulated on demand, in order, under a lock, as the first query reaches them: building a Sim costs nothing,
// and no run waits for motion it does not reach.
//
// Every block also has a broadphase over the movers (each mover's bounds over the block's time span, a frame of
// its window's BoxIndex: four blocks share clusters, so that the queries of a window's later blocks find them
// in the cache), so that the two questions the game asks of movers at a time t visit only the movers near the agent:
// the nearest point of any mover to a point (exact, per shape), and the first contact of an agent's sphere
// moving along a segment during a game step, by conservative advancement on exact distances (no tunnelling at
// any relative speed). Both give the answers of a visit of every mover, to the bit (the *_scan versions, kept
// for tests and for times outside the timeline).

#include <atomic>
#include <cstddef>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <vector>

#include "geometry/box_index.hpp"
#include "geometry/pose.hpp"
#include "geometry/ray.hpp"
#include "world/bodies/contact.hpp"
#include "world/map/map_spec.hpp"
#include "world/map/movers.hpp"
#include "world/map/triangle_mesh.hpp"

namespace peg3d::world {

/// A mover's point nearest to a query point, at some time.
struct MoverPoint {
  int mover = -1;             ///< index in MapSpec::movers; -1 when none is within the cap
  double distance = 0.0;      ///< m, >= 0 (0 inside the mover)
  Vec3 point = Vec3::Zero();  ///< the mover's point nearest to the query
};

/// The first mover a ray meets, at some time.
struct MoverHit {
  int mover = -1;         ///< index in MapSpec::movers; -1 when the ray meets none within its range
  double distance = 0.0;  ///< m along the ray (0 from inside a mover); the range when none
};

/// Makes mover m (of `shape`, posed at `at`) the `best` answer of a nearest-mover query at p when it is nearer
/// (the lower index among equally near ones); a test on its bounding ball (`reach`: shape.bounding_radius())
/// first spares the exact distance of the far.
void offer_nearer(int m, const Shape& shape, double reach, const Pose& at, const Vec3& p, MoverPoint& best);

/// Where a sphere of `radius` centred at c touches a posed shape: the shape's point nearest c (or, with c on or
/// inside the shape, the sphere's point along the normal) and the unit normal from the shape towards c (away
/// from the shape's centre when c lies on or inside it; +z when they coincide).
struct TouchPoint {
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();
};
TouchPoint touch_point(const Shape& shape, const Pose& at, const Vec3& c, double radius);

/// What a timeline holds and what it cost, for peg-map check and the performance pages.
struct TimelineStats {
  int dynamic_bodies = 0;
  int keyframe_hz = 0;                ///< keyframes per second of the dynamic bodies
  bool keyframe_hz_chosen = false;    ///< the map set no physics.keyframe_hz: the timeline chose it
  std::size_t every_substep_bytes = 0;  ///< the budget's estimate had every substep been kept
  std::size_t blocks = 0;             ///< blocks of the whole duration
  std::size_t blocks_simulated = 0;   ///< blocks built so far
  std::size_t worst_case_bytes = 0;   ///< the budget's estimate: every body moving all the time
  std::size_t bytes = 0;              ///< held now (poses and indices of the blocks built)
  std::size_t resting_entries = 0;    ///< (body, block) pairs stored once because the body was at rest
  std::size_t moving_entries = 0;     ///< (body, block) pairs stored at every keyframe
  double simulate_seconds = 0.0;      ///< s of wall time spent simulating and indexing so far
};

class MoverTimeline {
 public:
  /// Contacts closer than this count as touching (m): it bounds conservative advancement's work.
  static constexpr double kContactTolerance = 1e-4;
  /// The most advancement steps a contact search takes with one mover. A search that reaches it without an
  /// answer (an agent skimming a mover that moves fast, by a hair more than the tolerance) answers a contact at
  /// the last fraction it proved free (Contact::gave_up): never a missed one.
  static constexpr int kMaxAdvancementSteps = 100000;
  /// Most bytes a timeline may need in the worst case (every dynamic body moving for the whole duration).
  static constexpr std::size_t kMaxBytes = std::size_t{256} << 20;
  /// Length of a block, s (its keyframes are the nearest whole number at the keyframe rate, at least one).
  static constexpr double kBlockSeconds = 0.25;
  /// Blocks a window: one index serves the blocks of a window, each block a frame of its own (BoxIndex).
  static constexpr std::size_t kWindowBlocks = 4;
  /// The lowest keyframe rate (1/s) the timeline chooses for a map that sets no physics.keyframe_hz: sparser
  /// keyframes would draw the bodies' flight too coarsely to pass for their motion (a map may still ask for one).
  static constexpr int kMinChosenKeyframeHz = 10;

  /// The map's movers from 0 to at least `duration` s. `meshes` are the map's placed terrain meshes, in
  /// spec.meshes' order, kept by reference until every block is simulated (the Arena owns them). Throws MapError
  /// (naming physics.keyframe_hz and the estimate) when the worst case exceeds `max_bytes`; a map that sets no
  /// keyframe rate gets the highest one that fits (keyframe_rate()), and is refused only when none from
  /// kMinChosenKeyframeHz up does. Simulates nothing.
  /// Without `with_dynamic` the dynamic bodies are left out: never simulated, in no query (pose() gives their
  /// start), for push mode, where each run moves them in a world of its own.
  MoverTimeline(const MapSpec& spec, const std::vector<TriangleMesh>& meshes, double duration,
                std::size_t max_bytes = kMaxBytes, bool with_dynamic = true);
  ~MoverTimeline();
  MoverTimeline(const MoverTimeline&) = delete;
  MoverTimeline& operator=(const MoverTimeline&) = delete;

  int count() const { return static_cast<int>(movers_.size()); }
  const MoverSpec& mover(int m) const { return movers_[std::size_t(m)]; }
  /// s, the time the dynamic bodies are simulated to; past it they stay where they were.
  double duration() const { return duration_; }
  int rate_hz() const { return rate_hz_; }
  /// Substeps of the physics between two stored keyframes (1: every substep).
  int keyframe_stride() const { return stride_; }

  /// The pose of mover m at time t (s): exact for scripted movers; for dynamic bodies interpolated between the
  /// stored keyframes (positions linearly, orientations spherically).
  Pose pose(int m, double t) const;

  /// The movers' point nearest to p at time t, if any lies within `cap` m (the nearest, the lowest index among
  /// equally near ones). `hint`: a mover likely to be the answer (the last one near here, or -1), measured first
  /// so that the search starts with a tight bound; the answer does not depend on it. No allocation.
  MoverPoint nearest(const Vec3& p, double t, double cap, int hint = -1) const;

  /// The first mover the ray meets at time t within `range` (geometry/ray.hpp: exact in double precision; the
  /// lowest index among movers met at one distance), found through the window's index. No allocation.
  MoverHit first_along(const Ray& ray, double t, double range) const;

  /// first_along() for rays from one `origin` along the unit `directions` (at most BoxIndex::kFanRays): best[k]
  /// holds ray k's range on entry ({-1, range}) and its answer on return, the one first_along(ray, t, range)
  /// gives. One walk of the window's index serves them all, and each mover's pose is taken once. No allocation.
  void first_along_fan(const Vec3& origin, std::span<const Vec3> directions, double t, std::span<MoverHit> best) const;

  /// The first contact, during the step [t0, t0 + dt], of a sphere of `radius` moving from `from` to `to` at
  /// constant velocity with any mover (the earliest, the lowest index among equally early ones); nullopt when
  /// it touches none. A search that reaches kMaxAdvancementSteps answers conservatively (Contact::gave_up).
  /// No allocation.
  std::optional<Contact> first_contact(const Vec3& from, const Vec3& to, double radius, double t0,
                                            double dt) const;

  /// Writes to `out` (ascending, at most out.size()) the movers whose bounds over [t0, t1] come within `reach`
  /// of `box`: a superset of those within `reach` of it at any time of the interval. Returns how many there are
  /// (more than out.size() when they did not fit; then out holds none), or -1 when [t0, t1] lies outside the
  /// timeline (every mover may be near). No allocation.
  int candidates(const Box& box, double reach, double t0, double t1, std::span<int> out) const;

  /// Whether the dynamic bodies are in the queries (false: a timeline of the scripted movers, push mode).
  bool with_dynamic() const { return with_dynamic_; }
  /// The movers' point nearest to p at t = 0, within `cap`, dynamic bodies at their start included even when
  /// they are left out of the queries (for start checks).
  MoverPoint nearest_at_start(const Vec3& p, double cap) const;

  /// nearest(), first_along() and first_contact() by a visit of every mover: the reference the indexed queries must equal.
  MoverPoint nearest_scan(const Vec3& p, double t, double cap) const;
  MoverHit first_along_scan(const Ray& ray, double t, double range) const;
  std::optional<Contact> first_contact_scan(const Vec3& from, const Vec3& to, double radius, double t0,
                                                 double dt) const;

  /// The largest distance any point of mover m moves during [t0, t1] (a bound, m).
  double travel_bound(int m, double t0, double t1) const;

  /// A bound (m) on how far any point of any queried mover moves during [t0, t1] (within the timeline).
  double max_travel(double t0, double t1) const;

  /// Whether first_contact(from, to, radius, t0, dt) finds no contact, known from `clearance`: every queried
  /// mover lay at least that far (m) from `from` at t0 (the nearest() of that instant, or its cap when none
  /// was nearer). True only when no mover can close the gap to within kContactTolerance during the step, by
  /// the agent's travel and max_travel(): then the query need not run. False outside the timeline.
  bool clear_of_contact(double clearance, const Vec3& from, const Vec3& to, double radius, double t0,
                        double dt) const;

  /// The worst-case bytes of a map's timeline over `duration` s (what the budget is checked against), at the
  /// map's keyframe rate (every substep when it sets none), or keeping every `stride`-th substep.
  static std::size_t worst_case_bytes(const MapSpec& spec, double duration);
  static std::size_t worst_case_bytes(const MapSpec& spec, double duration, int stride);

  /// Substeps per keyframe of a map's timeline over `duration` s, and whether the timeline chose it: the map's
  /// physics.keyframe_hz; or, when it sets none, the smallest stride dividing rate_hz (the highest rate) whose
  /// worst case fits `max_bytes`, keeping at least kMinChosenKeyframeHz keyframes a second (when none fits,
  /// the stride of that lowest rate, which the constructor refuses).
  struct Rate {
    int stride = 1;
    bool chosen = false;
  };
  static Rate keyframe_rate(const MapSpec& spec, double duration, std::size_t max_bytes = kMaxBytes);

  /// What it holds now. Thread-safe.
  TimelineStats stats() const;
  /// Simulates every block now (the queries then never wait), for tools and benchmarks.
  void simulate_all() const { simulate_through(blocks_.size() - 1); }

 private:
  struct Block;
  class Simulation;

  /// The worst-case bytes of `keyframes` keyframes in `blocks` blocks of `dynamic` bodies, with `indexed` movers
  /// in each block's index.
  static std::size_t estimate(long keyframes, std::size_t blocks, std::size_t dynamic, std::size_t indexed);

  /// Block b, simulated first when it is not yet.
  const Block& block(std::size_t b) const;
  /// The index of block b's window (block b is its frame b % kWindowBlocks), simulated first when it is not yet.
  const BoxIndex& window(std::size_t b) const;
  /// Simulates every block through the end of block b's window.
  void simulate_through(std::size_t b) const;
  /// Block r's keyframes: the simulation advanced over it.
  std::unique_ptr<Block> simulate_block(std::size_t r) const;
  /// The queried movers' bounds over a block's time span (leaf i: queried_[i]); returns the most any point of a
  /// dynamic body moves over it (m).
  double bound_block(const Block& block, std::span<Box> bounds) const;
  std::size_t block_at(double t) const;
  /// Keyframe k (0..keyframes_) of dynamic body `row`.
  const Pose& keyframe(int row, long k) const;
  /// Whether [t0, t1] lies within the timeline, where the blocks' bounds hold.
  bool indexed(double t0, double t1) const { return t0 >= 0.0 && t1 <= duration_; }
  /// The contact of mover m during the step, if it comes before `best` (first_contact's per-mover work).
  void contact_with(int m, const Vec3& from, const Vec3& to, double radius, double t0, double dt,
                    std::optional<Contact>& best) const;
  /// Whether mover m at time t is nearer p than `best` (nearest's per-mover work).
  void nearer(int m, const Vec3& p, double t, MoverPoint& best) const;

  std::vector<MoverSpec> movers_;
  std::vector<ScriptedMotion> scripted_;  ///< per mover: its path or orbit, prepared (unused for dynamic bodies)
  std::vector<int> dynamic_index_;  ///< per mover: its row among the dynamic bodies, or -1 for scripted ones
  int dynamic_ = 0;
  bool with_dynamic_ = true;
  std::vector<int> queried_;         ///< the movers the queries look at, ascending: leaf i of a block's index is queried_[i]
  std::vector<Pose> start_poses_;    ///< per dynamic body, where it starts (its pose when left out)
  double scripted_speed_ = 0.0;      ///< m/s, the fastest queried scripted mover's speed bound
  std::vector<double> reach_;        ///< per mover: its shape's bounding radius
  double duration_ = 0.0;
  int rate_hz_ = 240;
  int stride_ = 1;            ///< substeps per keyframe
  bool keyframe_rate_chosen_ = false;  ///< stride_ chosen by keyframe_rate(), the map setting none
  std::size_t every_substep_bytes_ = 0;
  double keyframes_per_s_ = 240.0;
  long keyframes_ = 0;        ///< index of the last keyframe (keyframes 0..keyframes_)
  long block_keyframes_ = 1;  ///< keyframes per block (a block holds block_keyframes_ + 1, sharing its ends)
  std::size_t worst_case_bytes_ = 0;

  // Filled on demand, a window at a time: blocks_[b] and windows_[b / kWindowBlocks] are written once, under
  // simulate_mutex_, before ready_ passes b.
  mutable std::vector<std::unique_ptr<const Block>> blocks_;
  mutable std::vector<std::unique_ptr<const BoxIndex>> windows_;
  mutable std::vector<double> travel_;  ///< per block: the most any point of a dynamic body moves over it, m
  mutable std::atomic<std::size_t> ready_{0};
  mutable std::mutex simulate_mutex_;
  mutable std::unique_ptr<Simulation> simulation_;  ///< null once every block is built
  mutable std::atomic<std::size_t> bytes_{0};
  mutable std::size_t resting_entries_ = 0, moving_entries_ = 0;  // under simulate_mutex_
  mutable double simulate_seconds_ = 0.0;                         // under simulate_mutex_
};

}  // namespace peg3d::world
