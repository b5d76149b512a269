#pragma once
// FACL as a policy: the agent's percept becomes fuzzy inputs, one or two FACL learners (fuzzy::FaclLearner)
// produce the steering, and learn() applies the paper's TD updates.
//
// Features (all clamped into their partitions):
//   0 d_PE [0, target_range]   1 target azimuth error [-pi, pi]    2 target elevation error [-pi, pi]
//   3 d_O  [0, obstacle_range] 4 obstacle azimuth error [-pi, pi]  5 obstacle elevation error [-pi, pi]
// Channels by structure and angle inputs:
//   joint,  azimuth            -> one learner over {0,1,3,4}       -> (d_alpha, d_theta)   (the paper)
//   joint,  azimuth-elevation  -> one learner over {0,1,2,3,4,5}   -> (d_alpha, d_theta)
//   per-angle                  -> {0,1,3,4} -> d_alpha  and  {0,2,3,5} -> d_theta

#include <array>
#include <vector>

#include "fuzzy/facl_learner.hpp"
#include "game/policy.hpp"

namespace peg3d::game {

inline constexpr int kFeatureCount = 6;
using Features = std::array<double, kFeatureCount>;

/// The six features of a percept.
Features features_of(const Percept& p);

class FaclPolicy final : public Policy {
 public:
  FaclPolicy(const AgentConfig& config, Role role, std::uint64_t seed);

  void begin_episode(const AgentView& view, bool learning) override;
  Steering act(const AgentView& view) override;
  void learn(double reward, const AgentView& next, bool terminal) override;

  const AgentConfig& config() const { return config_; }
  Role role() const { return role_; }
  int channels() const { return static_cast<int>(channels_.size()); }
  fuzzy::FaclLearner& learner(int channel) { return channels_[channel].learner; }
  const fuzzy::FaclLearner& learner(int channel) const { return channels_[channel].learner; }

 private:
  struct Channel {
    fuzzy::FaclLearner learner;
    std::vector<int> features;   ///< indices into Features, fixed at construction
    std::array<int, 2> outputs;  ///< steering component of each learner output: 0 d_alpha, 1 d_theta
    std::array<fuzzy::FiredRules, 2> fired;  ///< current and successor state; `current` says which is which
    int current = 0;
    std::array<double, 2> u{}, u_explored{};
    fuzzy::FiredRules& now() { return fired[current]; }
    fuzzy::FiredRules& next() { return fired[1 - current]; }
  };

  void fire(Channel& c, const Features& f, fuzzy::FiredRules& out) const;

  AgentConfig config_;
  Role role_;
  std::vector<Channel> channels_;
  bool learning_ = false;
  bool have_now_ = false;  ///< learn() already fired the current state into Channel::now
};

}  // namespace peg3d::game
