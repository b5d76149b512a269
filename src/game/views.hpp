#pragma once
// How the agents of a state see it: the map's nearest obstacle at the state's time (its shapes and, on a map
// with moving obstacles, the nearer of them and the movers), and each agent's view rebuilt from the state.
// reset() and step() build every view this way; the guard's look-ahead senses through a StateProbe.

#include <limits>

#include "game/constraints.hpp"
#include "game/sim.hpp"

namespace peg3d::game {

/// The map's obstacle nearest to p at the state's time: its shapes only (whether the arena's faces count is the
/// agent's observation setting, not the map's) and, on a map with movers, the nearer of them and the field.
/// Movers are looked for within `reach` (m) only: beyond it the answer is the field's (ObstacleProbe::nearest).
/// With `mover`: it holds a hint, a mover likely to be the nearest (or -1; MoverTimeline::nearest), and gets the
/// timeline's answer (or -1), the next query's hint near here.
ObstacleSense sense_obstacle(const Sim& sim, const SimState& state, const Vec3& p,
                             double reach = std::numeric_limits<double>::infinity(), int* mover = nullptr);

/// The nearest occupied cell of agent i's own map to p (observation.obstacles = own-map), within the map's
/// distance cap (the field's, world::Arena::max_distance).
ObstacleSense sense_own_map(const Sim& sim, const SimState& state, int i, const Vec3& p);

/// The obstacle distance agent i's percept would read at p (its own map's nearest occupied cell, merged with the
/// arena's faces as its observation says): d_O before a move, measured again in the map the move's scan left.
double own_map_obstacle_distance(const Sim& sim, const SimState& state, int i, const Vec3& p);

/// The guard's look ahead senses as agent i does: in its own map, or in the world starting from the mover its
/// view found nearest (`hint`).
class StateProbe final : public ObstacleProbe {
 public:
  StateProbe(const Sim& sim, const SimState& state, int i, int hint) : sim_(sim), state_(state), i_(i), hint_(hint) {}
  ObstacleSense nearest(const Vec3& p, double reach) const override {
    if (state_.agents[std::size_t(i_)].config->observation.obstacles == ObstacleSource::kOwnMap) {
      return sense_own_map(sim_, state_, i_, p);
    }
    int hint = hint_;
    return sense_obstacle(sim_, state_, p, reach, &hint);
  }

 private:
  const Sim& sim_;
  const SimState& state_;
  int i_;
  int hint_;
};

/// Takes every agent's kinematics for the views' `team` spans: before the views of a reset or a step are rebuilt.
void snapshot_teams(SimState& state);

/// Rebuilds agent i's view from its position and its opponent's state (its `opponent` must be set).
void update_view(const Sim& sim, SimState& state, int i);

}  // namespace peg3d::game
