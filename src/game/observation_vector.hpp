#pragma once
// The observation vector of the Python front (env/batch.hpp, docs/python.md) as far as one agent's view
// holds it: the 20 entries every learner outside the C++ side sees, and what an MLP policy trained there
// reads back on the C++ side (game/mlp_policy.hpp). The neighbour slots that follow need the whole state and
// are the batch's.

#include "game/policy.hpp"

namespace peg3d::game {

/// Entries of observation_base.
inline constexpr int kObservationBase = 20;

/// Writes the view's 20 entries, float32:
///   [0]      d to the opponent, m                      the percept: the paper's fuzzy inputs (eq. 19-20)
///   [1, 2]   azimuth, elevation error to it, rad
///   [3]      d to the nearest obstacle, m (arena faces merged as configured)
///   [4, 5]   azimuth, elevation error to it, rad
///   [6..8]   own position, m
///   [9, 10]  own heading alpha, theta, rad
///   [11..13] opponent position minus own, m
///   [14..16] opponent velocity, m/s
///   [17..19] nearest obstacle point minus own position (movers included), m; 0 when none is in range
void observation_base(const AgentView& view, float* out);

}  // namespace peg3d::game
