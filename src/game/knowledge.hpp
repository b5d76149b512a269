#pragma once
// What agents know of their opponents when a detector limits it (limited sight: the sight sensor, sense/sight.hpp;
// SimState::sight, docs/sight.md): reset() gives every such agent a sighting of each opponent where it starts;
// after every reading (the reset's, then each step's, after the moves, captures and readings, before the new
// views) an agent's sightings of the opponents its detector sees become now, and teammates that share pool them.
// What an agent knows of an opponent is SimState::known_state().

#include "game/sim.hpp"

namespace peg3d::game {

/// Sizes `state.sight` for its agents (no allocation for a scenario no larger than before) and gives every agent
/// a sighting of each opponent at its start, time 0; empties it when no agent's sight is limited.
void prepare_sight(const Sim& sim, SimState& state);

/// Every agent in the game whose detector read now takes what it saw: a seen opponent's sighting becomes now.
/// Then teammates that share pool their sightings (the newest of each opponent; the lower index among equally new
/// ones). No allocation.
void look(const Sim& sim, SimState& state);

}  // namespace peg3d::game
