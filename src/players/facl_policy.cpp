#include "players/facl_policy.hpp"

#include <algorithm>
#include <cassert>
#include <stdexcept>

#include "core/random.hpp"
#include "core/step_profile.hpp"
#include "geometry/angles.hpp"

namespace peg3d::players {
namespace {

fuzzy::TriangularPartition partition_of(int feature, const game::ObservationConfig& o) {
  switch (feature) {
    case 0: return {0.0, o.target_range, o.sets, "observation.target_range"};
    case 3: return {0.0, o.obstacle_range, o.sets, "observation.obstacle_range"};
    case 8: return {0.0, 1.0, 2, "observation.sight_inputs"};
    case 9: return {0.0, o.sight_age_range, o.sets, "observation.sight_age_range"};
    default: return {-kPi, kPi, o.sets, "observation.angle"};
  }
}

fuzzy::RuleBase rule_base_of(const std::vector<int>& features, const game::ObservationConfig& o) {
  std::vector<fuzzy::TriangularPartition> parts;
  for (int f : features) parts.push_back(partition_of(f, o));
  return fuzzy::RuleBase(std::move(parts));
}

}  // namespace

Features features_of(const game::AgentView& v) {
  const game::Percept& p = v.percept;
  return {p.target_distance,   p.target.azimuth,      p.target.elevation,
          p.obstacle.distance,  p.to_obstacle.azimuth, p.to_obstacle.elevation,
          p.opponent_heading.azimuth, p.opponent_heading.elevation,
          v.other_visible ? 1.0 : 0.0, v.other_age};
}

FaclModel::FaclModel(const game::AgentConfig& config, game::Role role) : config_(config), role_(role) {
  struct Spec {
    std::vector<int> features;
    std::array<int, 2> outputs;
    int actions;
  };
  std::vector<Spec> specs;
  if (config.structure == game::FaclStructure::kPerAngle) {
    specs = {{{0, 1, 3, 4}, {0, -1}, 1}, {{0, 2, 3, 5}, {1, -1}, 1}};
  } else if (config.observation.angles == game::AngleInputs::kAzimuth) {
    specs = {{{0, 1, 3, 4}, {0, 1}, 2}};
  } else {
    specs = {{{0, 1, 2, 3, 4, 5}, {0, 1}, 2}};
  }
  if (config.observation.opponent_heading) {
    for (Spec& s : specs) {
      const bool azimuth = std::find(s.features.begin(), s.features.end(), 1) != s.features.end();
      const bool elevation = std::find(s.features.begin(), s.features.end(), 2) != s.features.end();
      if (azimuth) s.features.push_back(6);
      if (elevation) s.features.push_back(7);
    }
  }
  if (config.observation.sight_inputs) {
    for (Spec& s : specs) s.features.insert(s.features.end(), {8, 9});
  }
  channels_.reserve(specs.size());
  for (const Spec& s : specs) {
    channels_.push_back(
        Channel{fuzzy::FaclTables(rule_base_of(s.features, config.observation), s.actions, config.facl), s.features,
                s.outputs});
  }
}

void FaclModel::fire(int channel, const Features& f, fuzzy::FiredRules& out) const {
  const Channel& c = channels_[std::size_t(channel)];
  std::array<double, kFeatureCount> x;
  for (std::size_t i = 0; i < c.features.size(); ++i) x[i] = f[std::size_t(c.features[i])];
  c.tables.fire({x.data(), c.features.size()}, out);
}

FaclPolicy::FaclPolicy(const game::AgentConfig& config, game::Role role, std::uint64_t seed)
    : FaclPolicy(std::make_shared<FaclModel>(config, role), seed) {}

FaclPolicy::FaclPolicy(std::shared_ptr<FaclModel> model, std::uint64_t seed) : model_(model), trainable_(model.get()) {
  init_lanes(seed);
}

FaclPolicy::FaclPolicy(std::shared_ptr<const FaclModel> model) : model_(std::move(model)) { init_lanes(0); }

void FaclPolicy::init_lanes(std::uint64_t seed) {
  lanes_.reserve(std::size_t(model_->channels()));
  for (int c = 0; c < model_->channels(); ++c) {
    lanes_.push_back(Lane{&model_->tables(c), trainable_ != nullptr ? &trainable_->tables(c) : nullptr,
                          model_->outputs(c), model_->tables(c).actions(), c,
                          fuzzy::Exploration(model_->config().facl.exploration_variance, derive_seed(seed, {std::uint64_t(c)}))});
  }
}

void FaclPolicy::begin_episode(const game::AgentView&, bool learning) {
  if (learning && trainable_ == nullptr) throw std::logic_error("a FaclPolicy over a frozen model cannot learn");
  learning_ = learning;
  have_fired_ = false;
}

Steering FaclPolicy::act(const game::AgentView& view) {
  double steering[2] = {0.0, 0.0};
  const Features f = features_of(view);
  const bool reuse = have_fired_ && f == fired_features_;
  for (Lane& l : lanes_) {
    if (!reuse) {
      const StepProfile::Scope profiled(StepProfile::kFiring);
      model_->fire(l.channel, f, l.now());
    }
    const StepProfile::Scope profiled(StepProfile::kActorCritic);
    const std::size_t n = std::size_t(l.actions);
    if (learning_) {
      l.exploration.act(*l.tables, l.now(), {l.u.data(), n}, {l.u_explored.data(), n});
    } else {
      l.tables->act(l.now(), {l.u.data(), n});
      l.u_explored = l.u;
    }
    for (std::size_t j = 0; j < n; ++j) steering[l.outputs[j]] = l.u_explored[j];
  }
  have_fired_ = false;
  // The offset is added outside the learner: the actor's TD update compares explored and greedy outputs of
  // the same state, so the base turn cancels there.
  if (model_->config().action == game::FaclAction::kTargetLineOffset) {
    steering[0] += view.percept.target.azimuth;
    steering[1] += view.percept.target.elevation;
  }
  return {steering[0], steering[1]};
}

void FaclPolicy::learn(double reward, const game::AgentView& next, bool terminal) {
  assert(learning_ && trainable_ != nullptr);
  const Features f = features_of(next);
  for (Lane& l : lanes_) {
    const std::size_t n = std::size_t(l.actions);
    if (terminal) {
      const StepProfile::Scope profiled(StepProfile::kLearning);
      l.trainable->update(l.now(), {l.u.data(), n}, {l.u_explored.data(), n}, reward, nullptr);
    } else {
      {
        const StepProfile::Scope profiled(StepProfile::kFiring);
        model_->fire(l.channel, f, l.next());
      }
      const StepProfile::Scope profiled(StepProfile::kLearning);
      l.trainable->update(l.now(), {l.u.data(), n}, {l.u_explored.data(), n}, reward, &l.next());
      l.current = 1 - l.current;  // the successor's firing is the next act()'s current state
    }
  }
  fired_features_ = f;
  have_fired_ = !terminal;
}

}  // namespace peg3d::players
