// MlpPolicy (players/mlp_policy.hpp): the documented forward pass, and files that do not fit refused with the field.
#include "players/mlp_policy.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "game/observation.hpp"
#include "players/policy_io.hpp"
#include "view_writer.hpp"

namespace peg3d::players {
namespace {

using namespace peg3d::game;
using testing::WrittenView;

// A one-layer network 20 -> 2 that reads the target's azimuth and elevation errors (entries 1 and 2).
nlohmann::json steer_at_target(double gain) {
  nlohmann::json w = nlohmann::json::array();
  for (int j = 0; j < 2; ++j) {
    nlohmann::json row = nlohmann::json::array();
    for (int i = 0; i < kObservationBase; ++i) row.push_back(i == j + 1 ? gain : 0.0);
    w.push_back(row);
  }
  return {{"format", "peg3d-mlp"}, {"version", 1}, {"role", "pursuer"}, {"inputs", 20}, {"action_bound", 0.5},
          {"input_mean", std::vector<double>(20, 0.0)}, {"input_std", std::vector<double>(20, 1.0)},
          {"layers", {{{"weights", w}, {"bias", {0.0, 0.0}}}}}};
}

std::filesystem::path write(const nlohmann::json& doc, const std::string& name) {
  const auto file = std::filesystem::path(::testing::TempDir()) / name;
  std::ofstream(file) << doc.dump(1);
  return file;
}

TEST(MlpPolicy, ActsAsTheDocumentedForwardPass) {
  const auto file = write(steer_at_target(2.0), "steer.json");
  ASSERT_TRUE(is_mlp_document(read_policy_document(file).doc));
  MlpPolicy policy(load_mlp_policy(file, Role::kPursuer), 0);
  WrittenView w;
  AgentView& v = w.view;
  v.percept.target.azimuth = 0.3;
  v.percept.target.elevation = -0.1;
  const Steering u = policy.act(v);
  // bound * tanh(gain * x) of the float32 entries, with the library's tanh at run time (a constant expression
  // would be folded by the compiler, correctly rounded, where glibc's tanh may differ in the last bit)
  volatile double azimuth = double(0.3f), elevation = double(-0.1f);
  EXPECT_EQ(u.d_alpha, 0.5 * std::tanh(2.0 * azimuth));
  EXPECT_EQ(u.d_theta, 0.5 * std::tanh(2.0 * elevation));
}

TEST(MlpPolicy, HiddenLayersTakeTanhAndInputsAreNormalized) {
  nlohmann::json doc = steer_at_target(1.0);
  doc["input_mean"][1] = 0.1;
  doc["input_std"][1] = 0.5;
  doc["layers"].push_back({{"weights", {{3.0, 0.0}, {0.0, -1.0}}}, {"bias", {0.25, 0.0}}});
  MlpPolicy policy(load_mlp_policy(write(doc, "two.json"), Role::kPursuer), 0);
  WrittenView w;
  AgentView& v = w.view;
  v.percept.target.azimuth = 0.6;
  const Steering u = policy.act(v);
  volatile double azimuth = double(0.6f), zero = 0.0;
  const double h = std::tanh((azimuth - 0.1) * (1.0 / 0.5));
  EXPECT_EQ(u.d_alpha, 0.5 * std::tanh(0.25 + 3.0 * h));
  EXPECT_EQ(u.d_theta, 0.5 * std::tanh(-std::tanh(zero)));
}

TEST(MlpPolicy, ANetworkTrainedWithSightReadsTheSightEntriesLast) {
  // 20 + 2 inputs: d_alpha = bound tanh(in sight now), d_theta = bound tanh(0.1 x the sighting's age).
  nlohmann::json doc = steer_at_target(0.0);
  doc["inputs"] = 22;
  doc["input_mean"] = std::vector<double>(22, 0.0);
  doc["input_std"] = std::vector<double>(22, 1.0);
  for (int j = 0; j < 2; ++j) {
    doc["layers"][0]["weights"][std::size_t(j)].push_back(j == 0 ? 1.0 : 0.0);
    doc["layers"][0]["weights"][std::size_t(j)].push_back(j == 1 ? 0.1 : 0.0);
  }
  MlpPolicy policy(load_mlp_policy(write(doc, "sight.json"), Role::kPursuer), 0);
  for (const bool visible : {true, false}) {
    WrittenView w;
    AgentView& v = w.view;
    v.other_visible = visible;
    v.other_age = visible ? 0.0 : 3.5;
    const Steering u = policy.act(v);
    volatile double seen = visible ? 1.0 : 0.0, age = double(float(v.other_age));
    EXPECT_EQ(u.d_alpha, 0.5 * std::tanh(seen));
    EXPECT_EQ(u.d_theta, 0.5 * std::tanh(0.1 * age));
  }
}

TEST(MlpPolicy, PlayedBySampleItDrawsAboutTheMeanWithTheFilesStandardDeviations) {
  // "play": "sample": d_alpha, d_theta = the mean + action_std x N(0, 1) from the player's engine. Over 20 000
  // draws at three views each, the mean and standard deviation of (action - mean) / action_std are within 4.5
  // standard errors of 0 and 1, the two components are uncorrelated, and a seed gives one sequence.
  nlohmann::json doc = steer_at_target(2.0);
  doc["action_std"] = {0.05, 0.12};
  doc["play"] = "sample";
  const auto model = load_mlp_policy(write(doc, "sample.json"), Role::kPursuer);
  MlpPolicy mean_player(load_mlp_policy(write(steer_at_target(2.0), "mean.json"), Role::kPursuer), 0);
  for (const double azimuth : {-0.4, 0.0, 0.25}) {
    WrittenView w;
    AgentView& v = w.view;
    v.percept.target.azimuth = azimuth;
    v.percept.target.elevation = -0.5 * azimuth;
    const Steering mean = mean_player.act(v);
    for (const std::uint64_t seed : {1u, 77u}) {
      MlpPolicy a(model, seed), again(model, seed), other(model, seed + 1);
      const int n = 20000;
      double s[2] = {0, 0}, s2[2] = {0, 0}, cross = 0;
      bool same = true, differs = false;
      for (int k = 0; k < n; ++k) {
        const Steering u = a.act(v), w = again.act(v), x = other.act(v);
        same = same && u.d_alpha == w.d_alpha && u.d_theta == w.d_theta;
        differs = differs || u.d_alpha != x.d_alpha;
        const double z[2] = {(u.d_alpha - mean.d_alpha) / 0.05, (u.d_theta - mean.d_theta) / 0.12};
        for (int j = 0; j < 2; ++j) s[j] += z[j], s2[j] += z[j] * z[j];
        cross += z[0] * z[1];
      }
      EXPECT_TRUE(same);
      EXPECT_TRUE(differs);
      for (int j = 0; j < 2; ++j) {
        const double m = s[j] / n, var = s2[j] / n - m * m;
        EXPECT_NEAR(m, 0.0, 4.5 / std::sqrt(double(n))) << j;
        EXPECT_NEAR(var, 1.0, 4.5 * std::sqrt(2.0 / n)) << j;
      }
      EXPECT_NEAR(cross / n, 0.0, 4.5 / std::sqrt(double(n)));
    }
  }
  // Played by its mean (the default, or "play": "mean"), a file with action_std plays exactly the mean.
  doc["play"] = "mean";
  MlpPolicy by_mean(load_mlp_policy(write(doc, "by_mean.json"), Role::kPursuer), 5);
  WrittenView w;
  AgentView& v = w.view;
  v.percept.target.azimuth = 0.3;
  EXPECT_EQ(by_mean.act(v).d_alpha, mean_player.act(v).d_alpha);
}

TEST(MlpPolicy, FilesThatDoNotFitNameTheField) {
  const auto refuses = [](nlohmann::json doc, Role role, const std::string& field) {
    const auto file = write(doc, "bad.json");
    try {
      load_mlp_policy(file, role);
      ADD_FAILURE() << "accepted, expected an error at " << field;
    } catch (const PolicyFormatError& e) {
      EXPECT_EQ(e.field(), field) << e.what();
      EXPECT_NE(std::string(e.what()).find("bad.json"), std::string::npos);
    }
  };
  refuses(steer_at_target(1.0), Role::kEvader, "role");
  nlohmann::json d = steer_at_target(1.0);
  d["format"] = "peg3d-policy";
  refuses(d, Role::kPursuer, "format");
  d = steer_at_target(1.0);
  d["inputs"] = 21;
  refuses(d, Role::kPursuer, "inputs");
  d = steer_at_target(1.0);
  d["input_std"][4] = 0.0;
  refuses(d, Role::kPursuer, "input_std[4]");
  d = steer_at_target(1.0);
  d["layers"][0]["weights"][1].erase(3);
  refuses(d, Role::kPursuer, "layers[0].weights[1]");
  d = steer_at_target(1.0);
  d["layers"][0]["bias"][0] = "x";
  refuses(d, Role::kPursuer, "layers[0].bias[0]");
  d = steer_at_target(1.0);
  d["layers"][0]["weights"].erase(1);
  d["layers"][0]["bias"].erase(1);
  refuses(d, Role::kPursuer, "layers[0].weights");  // one output, not two
  d = steer_at_target(1.0);
  d["action_bound"] = -1;
  refuses(d, Role::kPursuer, "action_bound");
  d = steer_at_target(1.0);
  d["action_std"] = {0.1, 0.6};  // above the bound of 0.5
  refuses(d, Role::kPursuer, "action_std[1]");
  d["action_std"] = {0.1};
  refuses(d, Role::kPursuer, "action_std");
  d = steer_at_target(1.0);
  d["play"] = "sample";  // with no action_std
  refuses(d, Role::kPursuer, "play");
  d["action_std"] = {0.1, 0.1};
  d["play"] = "greedy";
  refuses(d, Role::kPursuer, "play");
}

}  // namespace
}  // namespace peg3d::players
