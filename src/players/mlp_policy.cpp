#include "players/mlp_policy.hpp"

#include <cmath>

#include <fmt/format.h>

#include "core/input_files.hpp"  // json_line_of
#include "game/observation_vector.hpp"
#include "players/policy_io.hpp"

namespace peg3d::players {

namespace {

constexpr long long kMaxWeights = 4'000'000;  // 32 MB of doubles: far beyond any policy of this game
constexpr int kMaxLayers = 16;

struct Reader {
  const std::filesystem::path& file;
  std::string_view text;
  [[noreturn]] void fail(const std::string& field, const std::string& message) const {
    throw PolicyFormatError(file, json_line_of(text, field), field, message);
  }
  const nlohmann::json& at(const nlohmann::json& j, const std::string& key, const std::string& field) const {
    if (!j.is_object() || !j.contains(key)) fail(field, "missing");
    return j.at(key);
  }
  double number(const nlohmann::json& j, const std::string& field) const {
    if (!j.is_number()) fail(field, "expects a number");
    const double v = j.get<double>();
    if (!std::isfinite(v)) fail(field, "must be finite");
    return v;
  }
  Eigen::VectorXd vector(const nlohmann::json& j, const std::string& field, long long size) const {
    if (!j.is_array()) fail(field, "expects a list of numbers");
    if (static_cast<long long>(j.size()) != size) fail(field, fmt::format("expects {} numbers, has {}", size, j.size()));
    Eigen::VectorXd v(size);
    for (long long k = 0; k < size; ++k) v[k] = number(j[std::size_t(k)], fmt::format("{}[{}]", field, k));
    return v;
  }
};

}  // namespace

bool is_mlp_document(const nlohmann::json& doc) {
  return doc.is_object() && doc.contains("format") && doc["format"] == kMlpFormat;
}

std::shared_ptr<const MlpModel> load_mlp_policy(const std::filesystem::path& file, game::Role role) {
  const PolicyDocument d = read_policy_document(file);
  return mlp_from_json(d.doc, file, role, d.text);
}

std::shared_ptr<const MlpModel> mlp_from_json(const nlohmann::json& doc, const std::filesystem::path& file, game::Role role,
                                              std::string_view text) {
  const Reader r{file, text};
  if (!is_mlp_document(doc)) {
    r.fail("format", fmt::format("expects \"{}\"", kMlpFormat));
  }
  if (r.at(doc, "version", "version") != kMlpVersion) r.fail("version", fmt::format("expects {}", kMlpVersion));
  auto m = std::make_shared<MlpModel>();
  const nlohmann::json& role_name = r.at(doc, "role", "role");
  if (role_name != "pursuer" && role_name != "evader") r.fail("role", "expects \"pursuer\" or \"evader\"");
  m->role = role_name == "pursuer" ? game::Role::kPursuer : game::Role::kEvader;
  if (m->role != role) r.fail("role", fmt::format("saved for the {}, asked to play the {}", to_string(m->role), to_string(role)));
  const double inputs = r.number(r.at(doc, "inputs", "inputs"), "inputs");
  const double rest = std::fmod(inputs - game::kObservationBase, 8.0);
  if (inputs < game::kObservationBase || inputs > game::kObservationBase + 2 * 16 * 4 + 2 || (rest != 0.0 && rest != 2.0)) {
    r.fail("inputs", "expects 20 + 8 k entries, k in [0, 16], or 2 more with limited sight");
  }
  m->inputs = static_cast<int>(inputs);
  m->sight = rest == 2.0;
  m->action_bound = r.number(r.at(doc, "action_bound", "action_bound"), "action_bound");
  if (!(m->action_bound > 0.0 && m->action_bound <= 3.2)) r.fail("action_bound", "expects a bound in (0, pi] rad");
  m->mean = r.vector(r.at(doc, "input_mean", "input_mean"), "input_mean", m->inputs);
  const Eigen::VectorXd std = r.vector(r.at(doc, "input_std", "input_std"), "input_std", m->inputs);
  for (int k = 0; k < m->inputs; ++k) {
    if (!(std[k] > 0.0)) r.fail(fmt::format("input_std[{}]", k), "must be > 0");
  }
  m->inv_std = std.cwiseInverse();
  const nlohmann::json& layers = r.at(doc, "layers", "layers");
  if (!layers.is_array() || layers.empty() || layers.size() > std::size_t(kMaxLayers)) {
    r.fail("layers", fmt::format("expects a list of 1 to {} layers", kMaxLayers));
  }
  long long in = m->inputs, total = 0;
  for (std::size_t l = 0; l < layers.size(); ++l) {
    const std::string field = fmt::format("layers[{}]", l);
    const nlohmann::json& w = r.at(layers[l], "weights", field + ".weights");
    if (!w.is_array() || w.empty()) r.fail(field + ".weights", "expects a list of rows");
    const long long out = static_cast<long long>(w.size());
    total += out * in;
    if (total > kMaxWeights) r.fail(field + ".weights", fmt::format("more than {} weights in all", kMaxWeights));
    Eigen::MatrixXd W(out, in);
    for (long long j = 0; j < out; ++j) {
      W.row(j) = r.vector(w[std::size_t(j)], fmt::format("{}.weights[{}]", field, j), in).transpose();
    }
    m->weights.push_back(std::move(W));
    m->biases.push_back(r.vector(r.at(layers[l], "bias", field + ".bias"), field + ".bias", out));
    in = out;
  }
  if (in != 2) r.fail(fmt::format("layers[{}].weights", layers.size() - 1), "the last layer must have 2 outputs (d_alpha, d_theta)");
  if (doc.contains("action_std")) {
    m->action_std = r.vector(doc["action_std"], "action_std", 2);
    for (int k = 0; k < 2; ++k) {
      if (!(m->action_std[k] >= 0.0 && m->action_std[k] <= m->action_bound)) {
        r.fail(fmt::format("action_std[{}]", k), "expects a standard deviation in [0, action_bound] rad");
      }
    }
  }
  if (doc.contains("play")) {
    const nlohmann::json& play = doc["play"];
    if (play != "mean" && play != "sample") r.fail("play", "expects \"mean\" or \"sample\"");
    m->sample = play == "sample";
    if (m->sample && !doc.contains("action_std")) r.fail("play", "\"sample\" needs the network's action_std");
  }
  return m;
}

MlpPolicy::MlpPolicy(std::shared_ptr<const MlpModel> model, std::uint64_t seed) : model_(std::move(model)), rng_(seed) {
  obs_.assign(std::size_t(model_->inputs), 0.0f);
  std::size_t widest = std::size_t(model_->inputs);
  for (const auto& w : model_->weights) widest = std::max(widest, std::size_t(w.rows()));
  a_.setZero(Eigen::Index(widest));
  b_.setZero(Eigen::Index(widest));
}

Steering MlpPolicy::act(const game::AgentView& view) {
  const MlpModel& m = *model_;
  game::observation_base(view, obs_.data());  // the neighbour slots stay empty (masks 0): the view has no others
  if (m.sight) {  // the two sight entries close the inputs, as they follow the neighbour slots in the batch's layout
    obs_[std::size_t(m.inputs - 2)] = view.other_visible ? 1.0f : 0.0f;
    obs_[std::size_t(m.inputs - 1)] = float(view.other_age);
  }
  for (int k = 0; k < m.inputs; ++k) a_[k] = (double(obs_[std::size_t(k)]) - m.mean[k]) * m.inv_std[k];
  Eigen::Index n = m.inputs;
  for (std::size_t l = 0; l < m.weights.size(); ++l) {
    const Eigen::MatrixXd& W = m.weights[l];
    const bool last = l + 1 == m.weights.size();
    for (Eigen::Index j = 0; j < W.rows(); ++j) {
      double s = m.biases[l][j];
      for (Eigen::Index i = 0; i < n; ++i) s += W(j, i) * a_[i];  // in order: the documented sum
      b_[j] = last ? s : std::tanh(s);
    }
    n = W.rows();
    std::swap(a_, b_);
  }
  Steering out{m.action_bound * std::tanh(a_[0]), m.action_bound * std::tanh(a_[1])};
  if (m.sample) {  // the game clamps the draw to the steering bound, as the batch clamps the learner's
    out.d_alpha += m.action_std[0] * normal_(rng_);
    out.d_theta += m.action_std[1] * normal_(rng_);
  }
  return out;
}

}  // namespace peg3d::players
