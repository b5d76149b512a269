#include "game/facl_policy.hpp"

#include <cassert>

#include "core/random.hpp"
#include "geometry/angles.hpp"

namespace peg3d::game {
namespace {

fuzzy::TriangularPartition partition_of(int feature, const ObservationConfig& o) {
  switch (feature) {
    case 0: return {0.0, o.target_range, o.sets, "observation.target_range"};
    case 3: return {0.0, o.obstacle_range, o.sets, "observation.obstacle_range"};
    default: return {-kPi, kPi, o.sets, "observation.angle"};
  }
}

fuzzy::RuleBase rule_base_of(const std::vector<int>& features, const ObservationConfig& o) {
  std::vector<fuzzy::TriangularPartition> parts;
  for (int f : features) parts.push_back(partition_of(f, o));
  return fuzzy::RuleBase(std::move(parts));
}

}  // namespace

Features features_of(const Percept& p) {
  return {p.target_distance, p.target.azimuth,      p.target.elevation,
          p.obstacle.distance, p.to_obstacle.azimuth, p.to_obstacle.elevation};
}

FaclPolicy::FaclPolicy(const AgentConfig& config, Role role, std::uint64_t seed) : config_(config), role_(role) {
  struct Spec {
    std::vector<int> features;
    std::array<int, 2> outputs;
    int actions;
  };
  std::vector<Spec> specs;
  if (config.structure == FaclStructure::kPerAngle) {
    specs = {{{0, 1, 3, 4}, {0, -1}, 1}, {{0, 2, 3, 5}, {1, -1}, 1}};
  } else if (config.observation.angles == AngleInputs::kAzimuth) {
    specs = {{{0, 1, 3, 4}, {0, 1}, 2}};
  } else {
    specs = {{{0, 1, 2, 3, 4, 5}, {0, 1}, 2}};
  }
  channels_.reserve(specs.size());
  for (std::size_t i = 0; i < specs.size(); ++i) {
    channels_.push_back(Channel{
        fuzzy::FaclLearner(rule_base_of(specs[i].features, config.observation), specs[i].actions, config.facl,
                           derive_seed(seed, {i})),
        specs[i].features, specs[i].outputs, {}, 0, {}, {}});
  }
}

void FaclPolicy::fire(Channel& c, const Features& f, fuzzy::FiredRules& out) const {
  std::array<double, kFeatureCount> x;
  for (std::size_t i = 0; i < c.features.size(); ++i) x[i] = f[c.features[i]];
  c.learner.fire({x.data(), c.features.size()}, out);
}

void FaclPolicy::begin_episode(const AgentView&, bool learning) {
  learning_ = learning;
  have_now_ = false;
}

Steering FaclPolicy::act(const AgentView& view) {
  double steering[2] = {0.0, 0.0};
  const Features f = have_now_ ? Features{} : features_of(view.percept);
  for (Channel& c : channels_) {
    if (!have_now_) fire(c, f, c.now());
    const int n = c.learner.actions();
    if (learning_) {
      c.learner.act_exploring(c.now(), {c.u.data(), std::size_t(n)}, {c.u_explored.data(), std::size_t(n)});
    } else {
      c.learner.act(c.now(), {c.u.data(), std::size_t(n)});
      c.u_explored = c.u;
    }
    for (int j = 0; j < n; ++j) steering[c.outputs[j]] = c.u_explored[j];
  }
  have_now_ = false;
  return {steering[0], steering[1]};
}

void FaclPolicy::learn(double reward, const AgentView& next, bool terminal) {
  assert(learning_);
  const Features f = features_of(next.percept);
  for (Channel& c : channels_) {
    const std::size_t n = c.learner.actions();
    if (terminal) {
      c.learner.update(c.now(), {c.u.data(), n}, {c.u_explored.data(), n}, reward, nullptr);
    } else {
      fire(c, f, c.next());
      c.learner.update(c.now(), {c.u.data(), n}, {c.u_explored.data(), n}, reward, &c.next());
      c.current = 1 - c.current;  // the successor's firing is the next act()'s current state
    }
  }
  have_now_ = !terminal;
}

}  // namespace peg3d::game
