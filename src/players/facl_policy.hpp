#pragma once
// FACL as a policy: the agent's percept becomes fuzzy inputs, one or two sets of FACL tables
// (fuzzy::FaclTables) produce the steering, and learn() applies the paper's TD updates.
//
//   FaclModel    what an agent has learned: its configuration (which fixes the inputs and rule bases) and one
//                set of tables per channel. Shareable: teammates that learn together share one model, and a
//                trained model serves greedy evaluations on any number of threads at once.
//   FaclPolicy   one agent driven by a model: its per-run scratch (the rules fired, the actions taken) and
//                its exploration engines. act() depends only on its argument and the model's tables.
//
// Features (all clamped into their partitions):
//   0 d_PE [0, target_range]   1 target azimuth error [-pi, pi]    2 target elevation error [-pi, pi]
//   3 d_O  [0, obstacle_range] 4 obstacle azimuth error [-pi, pi]  5 obstacle elevation error [-pi, pi]
//   6 opponent heading's azimuth error [-pi, pi]   7 its elevation error [-pi, pi]   (observation.opponent_heading)
//   8 the opponent in sight now {0, 1}   9 the age of its sighting [0, sight_age_range] s   (observation.sight_inputs)
// Channels by structure and angle inputs:
//   joint,  azimuth            -> one learner over {0,1,3,4}       -> (d_alpha, d_theta)   (the paper)
//   joint,  azimuth-elevation  -> one learner over {0,1,2,3,4,5}   -> (d_alpha, d_theta)
//   per-angle                  -> {0,1,3,4} -> d_alpha  and  {0,2,3,5} -> d_theta
// With opponent_heading, each channel also takes 6 (azimuth channels) or 7 (the elevation channel), or both
// (joint azimuth-elevation). With sight_inputs, every channel also takes 8 and 9.

#include <array>
#include <memory>
#include <vector>

#include "fuzzy/facl_learner.hpp"
#include "game/policy.hpp"

namespace peg3d::players {

inline constexpr int kFeatureCount = 10;
using Features = std::array<double, kFeatureCount>;

/// The features of a view (6 and 7 are 0 unless its percept observed the opponent's heading).
Features features_of(const game::AgentView& v);

/// The learned part of a FACL agent. Acting reads it; only a learning FaclPolicy writes it.
class FaclModel {
 public:
  /// Fresh tables (every consequent at its configured initial value) for `config`, which must select FACL.
  /// Throws InvalidParameter on a configuration the rule bases cannot be built from.
  FaclModel(const game::AgentConfig& config, game::Role role);

  const game::AgentConfig& config() const { return config_; }
  game::Role role() const { return role_; }
  int channels() const { return static_cast<int>(channels_.size()); }
  fuzzy::FaclTables& tables(int channel) { return channels_[std::size_t(channel)].tables; }
  const fuzzy::FaclTables& tables(int channel) const { return channels_[std::size_t(channel)].tables; }
  /// Which features feed a channel, and which steering component (0 d_alpha, 1 d_theta) each output drives.
  const std::vector<int>& features(int channel) const { return channels_[std::size_t(channel)].features; }
  const std::array<int, 2>& outputs(int channel) const { return channels_[std::size_t(channel)].outputs; }

  /// Fires channel c's rule base at the features f.
  void fire(int channel, const Features& f, fuzzy::FiredRules& out) const;

 private:
  struct Channel {
    fuzzy::FaclTables tables;
    std::vector<int> features;   ///< indices into Features
    std::array<int, 2> outputs;  ///< steering component of each output: 0 d_alpha, 1 d_theta
  };
  game::AgentConfig config_;
  game::Role role_;
  std::vector<Channel> channels_;
};

class FaclPolicy final : public game::Policy {
 public:
  /// A new model of its own for `config` (the one-agent-per-model case); `seed` seeds its exploration.
  FaclPolicy(const game::AgentConfig& config, game::Role role, std::uint64_t seed);
  /// An agent driven by a shared model that it may train; `seed` seeds its own exploration.
  FaclPolicy(std::shared_ptr<FaclModel> model, std::uint64_t seed);
  /// An agent driven by a frozen model: greedy only (begin_episode with learning throws std::logic_error).
  explicit FaclPolicy(std::shared_ptr<const FaclModel> model);

  void begin_episode(const game::AgentView& view, bool learning) override;
  Steering act(const game::AgentView& view) override;
  void learn(double reward, const game::AgentView& next, bool terminal) override;

  const FaclModel& model() const { return *model_; }
  /// The model, shareable with other agents or threads.
  std::shared_ptr<const FaclModel> shared_model() const { return model_; }

 private:
  /// One channel as this agent runs it: where its tables are, and its own scratch and noise.
  struct Lane {
    const fuzzy::FaclTables* tables;  ///< the model's (read while acting)
    fuzzy::FaclTables* trainable;     ///< the same tables when this policy may update them, else null
    std::array<int, 2> outputs;       ///< steering component of each output
    int actions;
    int channel;
    fuzzy::Exploration exploration;
    std::array<fuzzy::FiredRules, 2> fired{};  ///< current and successor state; `current` says which is which
    int current = 0;
    std::array<double, 2> u{}, u_explored{};
    fuzzy::FiredRules& now() { return fired[std::size_t(current)]; }
    fuzzy::FiredRules& next() { return fired[std::size_t(1 - current)]; }
  };

  void init_lanes(std::uint64_t seed);

  std::shared_ptr<const FaclModel> model_;
  FaclModel* trainable_ = nullptr;  ///< the same model when this policy may update it
  std::vector<Lane> lanes_;         ///< per channel
  bool learning_ = false;
  // learn() fires the successor state; act() on the same features reuses that firing instead of repeating it.
  Features fired_features_{};
  bool have_fired_ = false;
};

}  // namespace peg3d::players
