#include "players/mlp_policy.hpp"

#include <cmath>
#include <optional>
#include <stdexcept>

#include <fmt/format.h>

#include "core/input_files.hpp"  // json_line_of
#include "game/observation.hpp"
#include "players/policy_io.hpp"
#include "sense/sight.hpp"

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

// The observation a version 1 file's input count stands for, when only one does: the base entries (20), or the
// base entries and the sight entries (22, as version 1 defined them); nullopt otherwise.
std::optional<std::vector<sense::Segment>> version1_observation(int inputs) {
  if (inputs != game::kObservationBase && inputs != game::kObservationBase + 2) return std::nullopt;
  std::vector<sense::Segment> out;
  for (const game::ObservationEntry& e : game::kObservationEntries) out.push_back(sense::Segment::uniform(e.name, 1, e.unit, 0, 0, e.meaning));
  if (inputs > game::kObservationBase) sense::SightSensor(sense::SightConfig{}).segments({}, out);
  sense::lay_out(out);
  return out;
}

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
  const nlohmann::json& version = r.at(doc, "version", "version");
  if (version != 1 && version != kMlpVersion) r.fail("version", fmt::format("expects 1 or {}", kMlpVersion));
  auto m = std::make_shared<MlpModel>();
  const nlohmann::json& role_name = r.at(doc, "role", "role");
  if (role_name != "pursuer" && role_name != "evader") r.fail("role", "expects \"pursuer\" or \"evader\"");
  m->role = role_name == "pursuer" ? game::Role::kPursuer : game::Role::kEvader;
  if (m->role != role) r.fail("role", fmt::format("saved for the {}, asked to play the {}", game::to_string(m->role), game::to_string(role)));
  const double inputs = r.number(r.at(doc, "inputs", "inputs"), "inputs");
  if (!(inputs >= 1 && inputs <= 1 << 20) || inputs != std::floor(inputs)) r.fail("inputs", "expects a count in [1, 2^20]");
  m->inputs = static_cast<int>(inputs);
  if (version == 1) {
    // Version 1 recorded the input count alone; only counts that one observation gives are read.
    auto observation = version1_observation(m->inputs);
    if (!observation) {
      r.fail("inputs", fmt::format("a version 1 file records only its input count, and {} inputs can be neighbour slots "
                                   "or a sensor's readings: it would be guessed. Re-save it with the observation it was "
                                   "trained on: peg3d.upgrade_policy(FILE, env, AGENT) (docs/python.md, \"Policy files\")",
                                   m->inputs));
    }
    m->observation = std::move(*observation);
  } else {
    try {
      m->observation = sense::segments_from_json(r.at(doc, "observation", "observation"));
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      r.fail(what.substr(0, what.find(':')), what.substr(std::min(what.size(), what.find(':') + 2)));
    }
    if (sense::observation_size(m->observation) != m->inputs) {
      r.fail("inputs", fmt::format("{} inputs, but the observation's segments hold {}", m->inputs,
                                   sense::observation_size(m->observation)));
    }
  }
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

game::ObservationTable fit_observation(const MlpModel& model, const game::Sim& sim, game::Role role, int rank,
                                       const std::filesystem::path& file) {
  try {
    return game::bind_observation(sim, role, rank, model.observation);
  } catch (const std::invalid_argument& e) {
    throw PolicyFormatError(file, 0, "observation",
                            fmt::format("does not fit {} {} of this game: {}", game::to_string(role), rank, e.what()));
  }
}

MlpPolicy::MlpPolicy(std::shared_ptr<const MlpModel> model, std::uint64_t seed) : model_(std::move(model)), rng_(seed) {
  obs_.assign(std::size_t(model_->inputs), 0.0f);
  std::size_t widest = std::size_t(model_->inputs);
  for (const auto& w : model_->weights) widest = std::max(widest, std::size_t(w.rows()));
  a_.setZero(Eigen::Index(widest));
  b_.setZero(Eigen::Index(widest));
}

void MlpPolicy::bind(const game::AgentView& view) {
  if (view.observation == nullptr) throw std::logic_error("MlpPolicy: a view without its observation writer");
  if (bound_model_ == view.observation->model() && bound_agent_ == view.index) return;
  try {
    table_ = view.observation->bind(view.index, model_->observation);
  } catch (const std::invalid_argument& e) {
    throw PolicyFormatError(file(), 0, "observation", fmt::format("does not fit agent {} of this game: {}", view.index, e.what()));
  }
  bound_model_ = view.observation->model();
  bound_agent_ = view.index;
}

void MlpPolicy::begin_episode(const game::AgentView& view, bool) { bind(view); }

Steering MlpPolicy::act(const game::AgentView& view) {
  const MlpModel& m = *model_;
  bind(view);
  // What the batch gives this agent, by the same function (game::write_observation).
  view.observation->write(view.index, table_, obs_);
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
