#pragma once
// Where a scenario's agents start and whether the game can play that start: their positions kept radius inside
// the arena, and the overlaps (solid terrain, an obstacle, a mover at time 0, another agent when agents
// collide) that make a start unplayable. The Sim checks every scenario of its map once; reset() checks the
// start it is given.

#include <span>
#include <vector>

#include "core/error.hpp"
#include "game/game_config.hpp"
#include "world/arena.hpp"
#include "world/collision/collision_world.hpp"
#include "world/bodies/mover_timeline.hpp"

namespace peg3d::game {

/// A start that the game cannot play: an agent's sphere overlaps an obstacle or (when agents collide) another
/// agent. what() names the map file, the start's line and field, and what it overlaps.
class StartError : public InputError {
 public:
  using InputError::InputError;
};

/// Throws InvalidParameter when the scenario has no pursuer or no evader, or more than kMaxAgentsPerRole of
/// either.
void check_counts(const world::Scenario& scenario);

/// The start positions of a scenario's agents (pursuers first), each kept its radius inside the arena.
void start_positions(const world::Arena& arena, const GameConfig& config, const world::Scenario& scenario,
                     std::vector<Vec3>& out);

/// With the scenario's agents placed as bodies 0..n-1 of `world` at `positions` (radii set), throws StartError
/// for the first agent, in index order, that starts under solid terrain or whose sphere overlaps an obstacle,
/// a mover (at time 0; `movers` may be null) or, when agents collide, an earlier agent.
void check_start(const world::Arena& arena, const GameConfig& config, const world::MoverTimeline* movers,
                 const world::CollisionWorld& world, const world::Scenario& scenario, std::span<const Vec3> positions);

}  // namespace peg3d::game
