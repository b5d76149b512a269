#pragma once
// The agents' range sensors in a run (AgentConfig::lidar, SimState::scans): reset() prepares them and scans
// once; step() scans with the lidars whose period has come, after the agents moved, before their new views.

#include <cstdint>

#include "game/sim.hpp"

namespace peg3d::game {

/// Sizes `state.scans` for its agents (no allocation for a scenario no larger than before) and seeds each
/// sensing agent's stream from `seed` and its index. Nothing when no agent of the Sim has a lidar.
void prepare_scans(const Sim& sim, SimState& state, std::uint64_t seed);

/// Agent i scans now with its lidar (which it must have): the state's agents where they stand, the movers at
/// the state's time. No allocation.
void scan(const Sim& sim, SimState& state, int i);

/// The step's scans: every agent that took part in the step and whose lidar's period divides the step number.
void scan_due(const Sim& sim, SimState& state);

}  // namespace peg3d::game
