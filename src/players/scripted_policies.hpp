#pragma once
// Classic guidance laws and scripted evaders, as baselines for the learned agents. Each computes a desired
// direction and requests the heading change towards it (the game clamps it to the steering bound).

#include <optional>
#include <random>
#include <vector>

#include "core/random.hpp"
#include "geometry/half_spaces.hpp"
#include "game/policy.hpp"
#include "players/roadmap.hpp"

namespace peg3d::players {

/// A classic player, which the game plays free of its agent's motion space wherever it plays (game::Policy::scripted,
/// game::begin_playing), as the experiments always have (game::scripted_agent).
class ScriptedPolicy : public game::Policy {
 public:
  bool scripted() const override { return true; }
};

/// Pure pursuit: head straight at the opponent.
class PurePursuit final : public ScriptedPolicy {
 public:
  Steering act(const game::AgentView& view) override;
};

/// 3D proportional navigation: the velocity direction turns at N times the rotation rate of the line of
/// sight, omega = (r x v_rel) / |r|^2. While the target is behind (closing is impossible by PN alone) it
/// pursues directly.
class ProportionalNavigation final : public ScriptedPolicy {
 public:
  explicit ProportionalNavigation(double gain) : gain_(gain) {}
  Steering act(const game::AgentView& view) override;

 private:
  double gain_;
};

/// Apollonius interceptor: constant bearing to the point where the evader, holding its current heading,
/// meets the pursuer (the interception point on the Apollonius sphere), clamped into the arena; pure
/// pursuit when there is none.
class ApolloniusInterceptor final : public ScriptedPolicy {
 public:
  Steering act(const game::AgentView& view) override;
};

/// m: within this distance of the evader a VoronoiPursuer chases it (chosen among 1, 2, 4 and 8 m in OPEN's
/// scenarios, docs/learning.md).
inline constexpr double kVoronoiChase = 4.0;
/// s: a VoronoiPursuer whose team's sighting of the evader is older than this chases the estimate, as pn does: the
/// cell of a guessed position is a guess.
inline constexpr double kVoronoiSightAge = 1.0;

/// m: within this distance of the evader a geodesic VoronoiPursuer chases it (chosen among 2, 3 and 4 m in OPEN's
/// scenarios, docs/learning.md): its border point follows the evader's height, so it may close in further before
/// giving the cell up for the chase.
inline constexpr double kVoronoiGeodesicChase = 2.0;

/// s: a VoronoiPursuer partitions about the evader where it will be this much later at its speed and heading
/// (chosen among 0, 0.5, 1, 1.5 and 3 s in OPEN's scenarios, docs/learning.md).
inline constexpr double kVoronoiLead = 1.0;

/// How a VoronoiPursuer finds the evader's cell and its way to its goal.
enum class VoronoiWay {
  kStraight,  ///< the Euclidean cell, flown to straight (the obstacle guard slides it along the solids)
  kRoute,     ///< the Euclidean cell, gone round the solids by the roadmap where the straight way is not passable
  kGeodesic,  ///< the cell by shortest ways through the roadmap's open cells, gone round the solids as kRoute
};

/// How a VoronoiPursuer chases the evader once it chases (near it, without a face, or on an old sighting).
enum class VoronoiChase {
  kNavigation,    ///< proportional navigation
  kInterception,  ///< on a sighting at most kVoronoiSightAge old, toward where the evader's straight course at its
                  ///< speed meets this pursuer's (geometry/apollonius.hpp's interception_point), held in the arena;
                  ///< proportional navigation where the courses never meet
};

/// Voronoi pursuit for a team (Zhou, Zhang, Tomlin and Hoffmann, "Cooperative pursuit with Voronoi partitions",
/// Automatica 2016): the evader's Voronoi cell among the team is the region it reaches before any pursuer of equal
/// speed, and a pursuer whose cell borders it heads for the centroid of their shared face, which shrinks that
/// cell fastest. The evader is taken where it will be `kVoronoiLead` later. A pursuer with no such face, within
/// `kVoronoiChase` of that point, or of a team that has not seen the evader for `kVoronoiSightAge`, pursues by
/// proportional navigation.
/// - kStraight: obstacles are not in the cell. The face is the bisector plane of the two clipped by the arena and by
///   the other pursuers' bisectors (exactly, a convex polygon: geometry/plane_section.hpp).
/// - kRoute, with a probe (limited sight): as kStraight, but a pursuer whose straight way to its goal (the face's
///   centroid, or the evader it chases) is not passable (players/roadmap.hpp, kPassage) heads along the shortest way
///   of its Roadmap there instead, when there is one; else it flies straight.
/// - kGeodesic, with a probe: the cells are the Roadmap's geodesic partition (Roadmap::partition: distances along
///   shortest ways round the solids, cells 1 m wide), and the goal is the border point nearest the centroid of the
///   border it shares with the evader's cell (Roadmap::border_point), raised or lowered to the evader's height: a
///   faster evader slips over or under a pursuer that waits at mid-height. A pursuer whose cell shares no face with
///   the evader's, against an evader faster than itself, takes the border with the evader's geodesic Apollonius
///   cell instead (the cells the evader reaches first at its speed, Roadmap::partition with first_speed): around a
///   solid it cuts the other way round off, where it would trail the team. It chases within kVoronoiGeodesicChase
///   instead of kVoronoiChase. Gone to as kRoute. Without a probe, kStraight.
/// How it chases: `VoronoiChase`.
/// Its scratch (the cuts, the face, the roadmap's search) grows in the first calls and is reused after that.
class VoronoiPursuer final : public ScriptedPolicy {
 public:
  explicit VoronoiPursuer(double gain, VoronoiWay way = VoronoiWay::kStraight,
                          VoronoiChase chase = VoronoiChase::kNavigation)
      : chase_(gain), way_(way), chase_way_(chase) {}
  void begin_episode(const game::AgentView& view, bool learning) override;
  Steering act(const game::AgentView& view) override;

 private:
  // Whether this view plays kGeodesic: with a probe and the roadmap built from it.
  bool geodesic(const game::AgentView& view) const {
    return way_ == VoronoiWay::kGeodesic && view.probe != nullptr && roadmap_.cells() > 0;
  }
  // The centroid of the face this pursuer shares with the evader at e: Euclidean, or geodesic on the roadmap.
  std::optional<Vec3> face_goal(const game::AgentView& view, const Vec3& e);
  ProportionalNavigation chase_;
  VoronoiWay way_;
  VoronoiChase chase_way_;
  Roadmap roadmap_;                     // kRoute, kGeodesic: the grid of open cells
  std::vector<HalfSpace> cuts_;         // scratch: the other pursuers' bisectors
  std::vector<Vec3> face_, scratch_;    // scratch: the face's corners
  std::vector<Vec3> sources_;           // scratch: the evader, then the team, for the geodesic partition
};

/// Flee along the line of sight, away from the pursuer, pushed off the arena boundary and the nearest
/// obstacle by a repulsion that grows as they come within `kAvoidDistance`.
class FleeLineOfSight final : public ScriptedPolicy {
 public:
  Steering act(const game::AgentView& view) override;
};

/// Head for the farthest point from the pursuer of the evader's Apollonius dominance region (the ball of
/// points it reaches first) that lies inside the arena, with the same repulsion as FleeLineOfSight.
class FleeApollonius final : public ScriptedPolicy {
 public:
  Steering act(const game::AgentView& view) override;
};

/// Random heading changes, uniform within the steering bound, from the policy's own seeded engine.
class RandomWalk final : public ScriptedPolicy {
 public:
  RandomWalk(const SteeringConfig& steering, std::uint64_t seed) : steering_(steering), rng_(seed) {}
  Steering act(const game::AgentView& view) override;

 private:
  SteeringConfig steering_;
  Rng rng_;
  std::uniform_real_distribution<double> u_{-1.0, 1.0};
};

/// The heading change that turns the view's agent onto `direction` (any length; none for a zero vector).
Steering steer_toward(const game::AgentView& view, const Vec3& direction);

/// Distance (m) within which the scripted evaders feel the boundary and obstacles.
inline constexpr double kAvoidDistance = 4.0;

/// The scripted evaders' repulsion: the sum over the arena faces and the nearest obstacle within
/// kAvoidDistance of unit vectors away from them, weighted ((kAvoidDistance - d) / kAvoidDistance)^2 * 3.
Vec3 repulsion(const game::AgentView& view);

}  // namespace peg3d::players
