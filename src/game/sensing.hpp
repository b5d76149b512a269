#pragma once
// The agents' sensors in a run (AgentConfig::sensors, SimState::sensing), stepped through the sensor contract
// (sense/sensor.hpp) without knowing any by name: reset() prepares them and reads with each; step() reads with
// those whose period has come, after the agents moved, before their new views. A scan that feeds maps goes into its
// holder's own map at once.

#include <cstdint>

#include "game/sim.hpp"

namespace peg3d::game {

/// Sizes `state.sensing` for its agents (no allocation for a scenario no larger than before, carrying the same
/// sensors) and seeds each sensor's stream from `seed`, the sensor's tag and its holder's index. Empties it when no
/// agent of the Sim carries a sensor.
void prepare_sensing(const Sim& sim, SimState& state, std::uint64_t seed);

/// Agent i reads with its k-th sensor now: the state's agents where they stand, the movers at the state's time;
/// then, for a sensor that feeds maps, the scan goes into the agent's map. No allocation.
void scan(const Sim& sim, SimState& state, int i, int k);

/// Every sensor of agent i reads now (the reset's readings).
void scan_all(const Sim& sim, SimState& state, int i);

/// The step's readings: every sensor of every agent that took part in the step whose period divides the step number.
void scan_due(const Sim& sim, SimState& state);

}  // namespace peg3d::game
