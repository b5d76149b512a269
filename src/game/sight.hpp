#pragma once
// Opponents seen only in line of sight (AgentConfig::sight, SimState::sight, docs/sight.md): reset() gives every
// agent with limited sight a sighting of each opponent where it starts and looks; step() looks after the moves,
// captures and scans, before the new views. What an agent knows of an opponent is SimState::known_state().

#include "game/sim.hpp"

namespace peg3d::game {

/// Sizes `state.sight` for its agents (no allocation for a scenario no larger than before) and gives every agent
/// a sighting of each opponent at its start, time 0; empties it when no agent's sight is limited.
void prepare_sight(const Sim& sim, SimState& state);

/// Whether `eye`, an agent at `self` with `config`, sees the sphere (centre, radius) now: within range and field
/// of view, and a sight ray reaching it through the world at the state's time (sense/line_of_sight.hpp).
bool in_sight(const Sim& sim, const SimState& state, const sense::SightConfig& config, const KinematicState& self,
              const Vec3& centre, double radius);

/// Every agent in the game with limited sight looks at every opponent in the game: a seen one's sighting becomes
/// now. Then teammates that share pool their sightings (the newest of each opponent; the lower index among equally
/// new ones). No allocation.
void look(const Sim& sim, SimState& state);

}  // namespace peg3d::game
