#pragma once
// Classic players of the partial game (AgentConfig::sight, docs/sight.md): a pursuer that searches for an evader it
// has lost, and an evader that hides. With full information they play as pure pursuit and flee do.

#include <vector>

#include "players/roadmap.hpp"
#include "players/scripted_policies.hpp"

namespace peg3d::players {

/// Chases the evader while it sees it (pure pursuit); once it has lost it, flies to where its estimate puts it (the
/// last sighting, or dead reckoning from it) and, arrived there within kArrive, searches: it visits the points of
/// a lattice over the arena about kLattice apart, each time the one not visited since the evader was lost that is
/// nearest in the sum of its distances from the pursuer and from the point where the search began; with its own
/// map (AgentConfig::map), the points the map has not seen come first (the unknown space). A point counts
/// as visited when the pursuer passes within kVisit of it. When every point has been visited, the round starts
/// again. It heads straight for its goal (the obstacle guard keeps it off the solids). Stuck (no kProgress nearer
/// to its goal in kStuck, and the straight way there not passable: one of five segments, along the line and
/// kPassage off it on four sides, blocked as the view's SightProbe says), it takes a detour through the lattice
/// point it can pass to straight that is nearest in the sum of the two legs, those whose second leg is not
/// passable counting kBlockedLeg more; without a probe or a detour, it gives the goal up (a search point counts as
/// visited; an estimate as arrived at). Allocates in begin_episode() only.
class SearchPursuer final : public ScriptedPolicy {
 public:
  static constexpr double kLattice = 5.0;     ///< m between the search points along each axis (at most)
  static constexpr double kArrive = 1.5;      ///< m from the estimate at which the search begins
  static constexpr double kVisit = 2.5;       ///< m within which a search point counts as visited
  static constexpr double kProgress = 0.5;    ///< m nearer to its goal that counts as progress
  static constexpr double kStuck = 4.0;       ///< s without progress after which a blocked goal needs a detour
  static constexpr double kBlockedLeg = 10.0; ///< m added to a detour whose second leg is not passable
  static constexpr double kPassage = players::kPassage;  ///< m each side of a straight way that must be clear

  void begin_episode(const game::AgentView& view, bool learning) override;
  Steering act(const game::AgentView& view) override;

 private:
  void choose(const game::AgentView& view);
  int detour(const game::AgentView& view, const Vec3& goal) const;
  static bool passable(const game::AgentView& view, const Vec3& a, const Vec3& b);
  // Whether the agent has come no kProgress nearer to `goal` (known by `key`) for kStuck and cannot fly there
  // straight.
  bool stuck(const game::AgentView& view, int key, const Vec3& goal);
  std::vector<Vec3> points_;
  std::vector<double> visited_;  // s, when each point was last visited (-1: never)
  bool searching_ = false;
  double lost_at_ = 0.0;         // s, when the current round of the search began
  Vec3 search_from_ = Vec3::Zero();
  int target_ = -1;              // the search point it flies to
  int via_ = -1;                 // the lattice point of its detour
  int goal_key_ = -3;            // the goal progress is measured to: -2 the opponent, k search point k, 10000 + k detour k
  double goal_best_ = 0.0;       // m, the nearest it has come to it
  double goal_since_ = 0.0;      // s, when it last came kProgress nearer
};

/// When it sees its pursuer, or saw it less than kAlert ago, goes to a hiding place: among candidate points
/// around it (kHideAzimuths azimuths x 3 elevations, -30, 0 and 30 deg, x the distances kHideDistances, inside
/// the arena kHideMargin from its faces), one it can fly to in a straight line and that the pursuer, where the
/// evader takes it to be, cannot see (the view's SightProbe); the nearest, counting each metre it gains from the
/// pursuer as half a metre less. It keeps that place while the pursuer cannot see it there, and flies about it.
/// With no hiding place (or no probe: full information, or obstacles from its own map) it flees like
/// FleeLineOfSight. Allocates nothing.
class HideEvader final : public ScriptedPolicy {
 public:
  static constexpr double kAlert = 1.0;  ///< s after the last sighting during which it still looks for cover
  static constexpr int kHideAzimuths = 12;
  static constexpr double kHideDistances[3] = {2.5, 5.0, 8.0};  ///< m
  static constexpr double kHideMargin = 1.0;  ///< m

  void begin_episode(const game::AgentView& view, bool learning) override;
  Steering act(const game::AgentView& view) override;

 private:
  bool find_cover(const game::AgentView& view);
  bool has_spot_ = false;
  Vec3 spot_ = Vec3::Zero();
  FleeLineOfSight flee_;  // what it does without cover
};

}  // namespace peg3d::players
