#pragma once
// A policy trained outside the C++ side (examples/ppo_pursuer.py): a multilayer perceptron over the Python
// front's observation vector (game/observation_vector.hpp), evaluated here with Eigen and no torch, so that it
// plays wherever a policy plays. The file (docs/python.md, "Policy files"), JSON:
//   {"format": "peg3d-mlp", "version": 1, "role": "pursuer" | "evader",
//    "inputs": 20 + 8 k (k neighbours, seen empty on the C++ side), plus 2 for a network trained with limited
//              sight (the sight entries of env/batch.hpp's layout: in sight now, the sighting's age), "action_bound": rad,
//    "input_mean": [inputs], "input_std": [inputs] (> 0),
//    "layers": [{"weights": [[in] x out], "bias": [out]}, ...],
//    optional: "action_std": [2] rad in [0, action_bound], the Gaussian the network was trained with;
//              "play": "mean" (default) or "sample" (needs action_std)}
// act(): x = (obs - mean) / std; tanh after every layer but the last; the action is action_bound * tanh(out),
// out = (d_alpha, d_theta). Every sum runs in double over the inputs in order (weights[j][0] x[0] first), so a
// reference in another language that sums in the same order gets the same bits. With "play": "sample" the
// action is drawn about that mean with action_std, as PPO drew it in training, from the player's own engine
// (seeded per agent by the caller): a policy trained with noise can rely on it, for example to leave a spot
// where its mean action holds it still (docs/learning.md, the partial game).

#include <cstdint>
#include <filesystem>
#include <memory>
#include <random>
#include <string_view>
#include <vector>

#include <Eigen/Dense>
#include <nlohmann/json.hpp>

#include "game/policy.hpp"

namespace peg3d::players {

inline constexpr const char* kMlpFormat = "peg3d-mlp";
inline constexpr int kMlpVersion = 1;

struct MlpModel {
  game::Role role = game::Role::kPursuer;
  int inputs = 0;
  bool sight = false;  ///< its last two inputs are the sight entries (in sight now, the sighting's age)
  double action_bound = 0.0;  ///< rad, > 0
  Eigen::Vector2d action_std = Eigen::Vector2d::Zero();  ///< rad, in [0, action_bound]; 0 when the file has none
  bool sample = false;  ///< "play": "sample": actions drawn about the mean with action_std
  Eigen::VectorXd mean, inv_std;
  std::vector<Eigen::MatrixXd> weights;  ///< out x in
  std::vector<Eigen::VectorXd> biases;
};

/// The MLP model of a policy document (read_policy_document) for `role`; one that does not fit is a
/// PolicyFormatError (an InputError) naming `file`, the field and, from `text`, its line.
std::shared_ptr<const MlpModel> mlp_from_json(const nlohmann::json& doc, const std::filesystem::path& file, game::Role role,
                                              std::string_view text);
/// Loads an MLP policy file for `role`: read_policy_document, then mlp_from_json.
std::shared_ptr<const MlpModel> load_mlp_policy(const std::filesystem::path& file, game::Role role);

/// Whether a policy document is an MLP one (its "format"); false for anything else, FACL documents included.
bool is_mlp_document(const nlohmann::json& doc);

class MlpPolicy final : public game::Policy {
 public:
  /// `seed` feeds the draws of a sampling model; a model played by its mean draws nothing.
  MlpPolicy(std::shared_ptr<const MlpModel> model, std::uint64_t seed);
  Steering act(const game::AgentView& view) override;

 private:
  std::shared_ptr<const MlpModel> model_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_;
  std::vector<float> obs_;
  Eigen::VectorXd a_, b_;
};

}  // namespace peg3d::players
