#pragma once
// Who an agent is in a game: its role (pursuer or evader), its rank among the agents of that role, and the one
// name peg3d gives it everywhere.

#include <string>

namespace peg3d::game {

enum class Role { kPursuer, kEvader };
const char* to_string(Role r);

/// Agent i of a game's order (a scenario's, a SimState's): `pursuers` pursuers first, then the evaders. Its
/// role, and its rank k among the agents of that role.
constexpr Role role_at(int i, int pursuers) { return i < pursuers ? Role::kPursuer : Role::kEvader; }
constexpr int rank_at(int i, int pursuers) { return i < pursuers ? i : i - pursuers; }
/// The role an agent of `role` plays against.
constexpr Role opposing(Role role) { return role == Role::kPursuer ? Role::kEvader : Role::kPursuer; }
/// The one name of agent `rank` (0 first) of a role, everywhere peg3d names agents: trajectory files, collision
/// logs and cases, replays, results, Python (its agents, its `opponents` keys): "pursuer_0", "evader_1", ... The
/// "<group>_<int>" form is the one multi-agent libraries group agents by (TorchRL, VMAS, BenchMARL).
std::string agent_label(Role role, int rank);

/// A label in the current form for one peg3d wrote before issue 37 (collision logs of format 1, collision cases,
/// trajectory files): the role alone, which named the only agent of its role ("pursuer" -> "pursuer_0"), or role
/// and rank run together ("evader1" -> "evader_1"). Any other text comes back unchanged.
std::string current_agent_label(const std::string& label);

}  // namespace peg3d::game
