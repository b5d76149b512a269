#pragma once
// How several pursuers and evaders play together: who plays against whom, which agents collide, who is paid
// for a capture. The rules act in game/step.cpp and game/sim.cpp (choose_opponent).

#include <concepts>
#include <type_traits>

#include "core/config_fields.hpp"

#include "game/role.hpp"

namespace peg3d::game {

/// Which opponent an agent observes, is rewarded against and (with the motion space) steers relative to.
enum class OpponentChoice {
  kNearest,   ///< the nearest opponent still in the game (ties: the lower index)
  kAssigned,  ///< opponent k mod n for the agent's index k among its role, while that one is in the game;
              ///< the nearest one after
};
inline constexpr config::EnumNames<OpponentChoice, 2> kOpponentChoiceNames{
    {{OpponentChoice::kNearest, "nearest"}, {OpponentChoice::kAssigned, "assigned"}}};

/// Which pairs of agents collide with each other (spheres of their radii, swept over each step).
enum class AgentCollisions {
  kNone,       ///< agents pass through each other (the paper)
  kOpponents,  ///< pursuers with evaders
  kTeammates,  ///< pursuers with pursuers and evaders with evaders
  kAll,        ///< every pair
};
inline constexpr config::EnumNames<AgentCollisions, 4> kAgentCollisionNames{{{AgentCollisions::kNone, "none"},
                                                                            {AgentCollisions::kOpponents, "opponents"},
                                                                            {AgentCollisions::kTeammates, "teammates"},
                                                                            {AgentCollisions::kAll, "all"}}};

/// Who receives the capture term r_s of a capture.
enum class CaptureReward {
  kIndividual,  ///< the capturing pursuer (+gamma_s) and the captured evader (-gamma_s)
  kTeam,        ///< every pursuer (+gamma_s), and the captured evader and every evader still free (-gamma_s)
};
inline constexpr config::EnumNames<CaptureReward, 2> kCaptureRewardNames{
    {{CaptureReward::kIndividual, "individual"}, {CaptureReward::kTeam, "team"}}};


/// How several pursuers and evaders play together (the paper's 1 v 1 is a team of one each).
struct TeamConfig {
  OpponentChoice pursuer_target = OpponentChoice::kNearest;  ///< the evader a pursuer plays against
  OpponentChoice evader_threat = OpponentChoice::kNearest;   ///< the pursuer an evader plays against
  AgentCollisions agent_collisions = AgentCollisions::kNone;
  CaptureReward capture_reward = CaptureReward::kIndividual;
  bool operator==(const TeamConfig&) const = default;

  /// The rule by which an agent of `role` chooses its opponent.
  OpponentChoice opponent_rule(Role role) const { return role == Role::kPursuer ? pursuer_target : evader_threat; }
  /// Whether an agent of role a and one of role b collide (agent_collisions).
  bool collide(Role a, Role b) const {
    switch (agent_collisions) {
      case AgentCollisions::kNone: return false;
      case AgentCollisions::kOpponents: return a != b;
      case AgentCollisions::kTeammates: return a == b;
      case AgentCollisions::kAll: return true;
    }
    return false;
  }
};

template <class V, class C>
  requires std::same_as<std::remove_const_t<C>, TeamConfig>
void visit_fields(V& v, C& c) {
  v.choice("pursuer_target", c.pursuer_target, kOpponentChoiceNames, "the evader each pursuer plays against");
  v.choice("evader_threat", c.evader_threat, kOpponentChoiceNames, "the pursuer each evader plays against");
  v.choice("agent_collisions", c.agent_collisions, kAgentCollisionNames, "which pairs of agents collide");
  v.choice("capture_reward", c.capture_reward, kCaptureRewardNames, "who receives the capture term r_s");
}

}  // namespace peg3d::game
