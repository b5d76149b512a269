#pragma once
// A policy trained outside the C++ side (peg3d.save_policy in Python, docs/python.md): a multilayer perceptron over
// the agent's observation (game/observation.hpp), evaluated here with Eigen and no torch, so that it plays wherever
// a policy plays, fed exactly what the Python front's batch gives that agent: the same function writes both. The
// file (docs/python.md, "Policy files"), JSON:
//   {"format": "peg3d-mlp", "version": 2, "role": "pursuer" | "evader",
//    "observation": [{"name", "size", "unit"}, ...], the segments of the observation it reads (sense/segment.hpp), in
//              order; playing it for an agent whose observation differs is refused, naming the first segment that
//              differs,
//    "inputs": their total size, "action_bound": rad,
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
//
// Version 1 files record only their input count, which several observations give (k neighbour slots or a lidar's
// ranges, for one). Those of 20 inputs (the base entries) and 22 (with the sight entries, as version 1 defined)
// read one way and still play; any other is refused with how to re-save it (peg3d.upgrade_policy).

#include <cstdint>
#include <filesystem>
#include <memory>
#include <random>
#include <string_view>
#include <vector>

#include <Eigen/Dense>
#include <nlohmann/json.hpp>

#include "game/observation.hpp"
#include "game/policy.hpp"
#include "game/sim.hpp"

namespace peg3d::players {

inline constexpr const char* kMlpFormat = "peg3d-mlp";
inline constexpr int kMlpVersion = 2;  // 2: the observation's segments

struct MlpModel {
  game::Role role = game::Role::kPursuer;
  int inputs = 0;
  std::vector<sense::Segment> observation;  ///< what it reads, in order (offsets laid out; no bounds)
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

/// The table of agent `rank` of `role` in `sim` that `model` reads; a model whose observation the agent's does not
/// give is a PolicyFormatError naming `file`, the field "observation" and the first segment that differs.
game::ObservationTable fit_observation(const MlpModel& model, const game::Sim& sim, game::Role role, int rank,
                                       const std::filesystem::path& file);

class MlpPolicy final : public game::Policy {
 public:
  /// `seed` feeds the draws of a sampling model; a model played by its mean draws nothing.
  MlpPolicy(std::shared_ptr<const MlpModel> model, std::uint64_t seed);
  /// Binds the model's observation to the view's agent (once per game model and agent: no allocation after).
  void begin_episode(const game::AgentView& view, bool learning) override;
  Steering act(const game::AgentView& view) override;

 private:
  void bind(const game::AgentView& view);
  std::shared_ptr<const MlpModel> model_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_;
  std::vector<float> obs_;
  Eigen::VectorXd a_, b_;
  game::ObservationTable table_;       // the model's observation, bound to the agent it plays
  const void* bound_model_ = nullptr;  // the game model (ObservationWriter::model) and agent it is bound to
  int bound_agent_ = -1;
};

}  // namespace peg3d::players
