#pragma once
// Random starts: a curriculum over start places for training (experiment/training.hpp, random_starts). The map's scenarios
// give a handful of starts; an agent trained from them alone meets, in a held-out map, places it never
// started from (a corner, a wall at its back). A random start keeps the scenario's agents and draws their
// places anew from the episode's own seed.

#include <cstdint>

#include "game/sim.hpp"
#include "world/map/map_spec.hpp"

namespace peg3d::game {

/// Clearance (m) a random start keeps, beyond an agent's radius, from the arena's faces and the map's shapes.
inline constexpr double kRandomStartClearance = 0.5;

/// A start with `like`'s agents (its names and counts, none of its places or headings): each agent at a place
/// drawn uniformly from the arena box shrunk by its radius plus kRandomStartClearance, as clear of the map's
/// shapes (and of its movers at t = 0), and not under solid terrain. Each pursuer lies more than
/// max(gap, capture_distance) from each evader (gap in m); agents of one role lie at least their
/// two radii plus the clearance apart. When 1000 draws find no place for some agent, `like` itself is returned
/// (Sim checked it), so no run fails on its start. A pure function of its arguments.
world::Scenario random_start(const Sim& sim, const world::Scenario& like, std::uint64_t seed, double gap);

}  // namespace peg3d::game
