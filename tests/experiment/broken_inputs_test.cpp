// Configurations and policy files a user can get wrong: each is refused with an InputError naming the file,
// the line and the field. The configuration corpus is tests/data/configs/broken/ (its expect.txt says what
// each file must report); policies are a saved policy with one thing broken, made here.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <string>

#include <fmt/format.h>

#include "core/error.hpp"
#include "experiment/trial_config.hpp"
#include "players/facl_policy.hpp"
#include "game/game_config.hpp"
#include "players/policy_io.hpp"
#include "support/scratch_dir.hpp"

namespace peg3d::experiment {
namespace {

namespace fs = std::filesystem;

const fs::path kConfigs = fs::path(PEG3D_TEST_DATA_DIR) / "configs" / "broken";

struct Expectation {
  int line = 0;
  std::string field;
  std::string fragment;
};

std::map<std::string, Expectation> config_expectations() {
  std::map<std::string, Expectation> out;
  std::ifstream in(kConfigs / "expect.txt");
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream words(line);
    std::string file, field;
    Expectation e;
    words >> file >> e.line >> field;
    std::getline(words >> std::ws, e.fragment);
    e.field = field == "-" ? "" : field;
    out[file] = e;
  }
  return out;
}

void expect_error(const InputError& e, const fs::path& file, const Expectation& want) {
  const std::string what = e.what();
  EXPECT_EQ(e.file(), file) << what;
  EXPECT_EQ(e.line(), want.line) << what;
  EXPECT_EQ(e.field(), want.field) << what;
  EXPECT_NE(e.message().find(want.fragment), std::string::npos) << what;
  EXPECT_LT(what.size(), 400u) << "a message quotes the user's text briefly";
}

TEST(ExperimentBrokenInputs, EveryBrokenConfigurationIsRefusedAsExpected) {
  const auto expectations = config_expectations();
  int files = 0;
  for (const auto& entry : fs::directory_iterator(kConfigs)) {
    if (entry.path().extension() != ".json") continue;
    ++files;
    const std::string name = entry.path().filename().string();
    SCOPED_TRACE(name);
    const auto want = expectations.find(name);
    ASSERT_NE(want, expectations.end()) << "expect.txt has no line for " << name;
    try {
      load_trial_config(entry.path().string());
      ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
      expect_error(e, entry.path(), want->second);
    }
  }
  EXPECT_EQ(files, static_cast<int>(expectations.size())) << "expect.txt names a file that is not there";
}

class ExperimentBrokenPolicy : public ::testing::Test {
 protected:
  void SetUp() override {
    const game::AgentConfig config = game::agent_preset("peg3d", game::Role::kPursuer);
    good_ = players::policy_to_json(players::FaclModel(config, game::Role::kPursuer));
  }

  // Writes the good policy changed by `edit` (pretty-printed, so fields sit on their own lines) and loads it.
  void expect_refused(const std::function<void(nlohmann::json&)>& edit, const Expectation& want) {
    nlohmann::json doc = good_;
    edit(doc);
    write_and_expect(doc.dump(1), want);
  }
  void write_and_expect(const std::string& text, const Expectation& want) {
    const fs::path file = dir_ / "policy.json";
    std::ofstream(file, std::ios::binary) << text;
    try {
      players::load_policy(file, game::Role::kPursuer);
      ADD_FAILURE() << "accepted";
    } catch (const players::PolicyFormatError& e) {
      expect_error(e, file, want);
    }
  }
  // The line `needle` is on in the pretty-printed policy changed by `edit`.
  int line_of(const std::function<void(nlohmann::json&)>& edit, const std::string& needle) {
    nlohmann::json doc = good_;
    edit(doc);
    const std::string text = doc.dump(1);
    const std::size_t at = text.find(needle);
    return at == std::string::npos ? -1 : 1 + static_cast<int>(std::count(text.begin(), text.begin() + long(at), '\n'));
  }

  peg3d::testing::ScratchDir scratch_;  // before dir_, which copies its path
  fs::path dir_ = scratch_.path();
  nlohmann::json good_;
};

TEST_F(ExperimentBrokenPolicy, TheUnbrokenPolicyLoads) {
  const fs::path file = dir_ / "good.json";
  std::ofstream(file) << good_.dump(1);
  EXPECT_NE(players::load_policy(file, game::Role::kPursuer), nullptr);
}

TEST_F(ExperimentBrokenPolicy, TablesOfTheWrongShapeAreRefused) {
  const std::size_t actor = good_["channels"][0]["actor"].size();
  expect_refused([](nlohmann::json& d) { d["channels"][0]["actor"].erase(0); },
                 {line_of([](nlohmann::json& d) { d["channels"][0]["actor"].erase(0); }, "\"actor\""), "channels[0].actor",
                  fmt::format("has {} entries, this configuration needs {}", actor - 1, actor)});
  expect_refused([](nlohmann::json& d) { d["channels"][0]["critic"] = 3; },
                 {line_of([](nlohmann::json& d) { d["channels"][0]["critic"] = 3; }, "\"critic\""), "channels[0].critic",
                  "expects a list of numbers"});
  expect_refused([](nlohmann::json& d) { d["channels"][0]["rules"] = 7; },
                 {line_of([](nlohmann::json&) {}, "\"channels\"") + 1, "channels[0]", "has 7 rules"});
  expect_refused([](nlohmann::json& d) { d["channels"].push_back(d["channels"][0]); },
                 {line_of([](nlohmann::json&) {}, "\"channels\""), "channels",
                  fmt::format("expected a list of {} channels", good_["channels"].size())});
  expect_refused([](nlohmann::json& d) { d["channels"][0] = "x"; },
                 {line_of([](nlohmann::json&) {}, "\"channels\"") + 1, "channels[0]", "expects an object"});
}

TEST_F(ExperimentBrokenPolicy, NonFiniteAndNonNumericTableValuesAreRefused) {
  // JSON has no NaN: nlohmann writes one as null, and 1e999 overflows the parser.
  const auto nan = [](nlohmann::json& d) { d["channels"][0]["critic"][3] = std::nan(""); };
  expect_refused(nan, {line_of([](nlohmann::json&) {}, "\"critic\"") + 4, "channels[0].critic[3]", "expects a number, got null"});
  expect_refused([](nlohmann::json& d) { d["channels"][0]["actor"][0] = "1"; },
                 {line_of([](nlohmann::json&) {}, "\"actor\"") + 1, "channels[0].actor[0]", "expects a number, got \"1\""});
  std::string text = good_.dump(1);
  const std::size_t at = text.find("\"critic\": [\n") + 12;
  const std::size_t end = text.find(',', at);
  text.replace(at, end - at, "1e999");
  write_and_expect(text, {0, "", "number overflow"});
}

TEST_F(ExperimentBrokenPolicy, HeaderAndConfigurationMistakesNameTheirField) {
  expect_refused([](nlohmann::json& d) { d.erase("format"); }, {0, "format", "not a peg3d policy"});
  expect_refused([](nlohmann::json& d) { d["version"] = 99; }, {line_of([](nlohmann::json&) {}, "\"version\""), "version", "99 is not supported"});
  expect_refused([](nlohmann::json& d) { d["role"] = std::string(100000, 'r'); },
                 {line_of([](nlohmann::json&) {}, "\"role\""), "role", "must be \"pursuer\" or \"evader\", got \"rrrr"});
  expect_refused([](nlohmann::json& d) { d["role"] = "evader"; }, {line_of([](nlohmann::json&) {}, "\"role\""), "role", "it cannot play the pursuer"});
  expect_refused([](nlohmann::json& d) { d["config"].erase("speed"); }, {0, "config.speed", "missing"});
  expect_refused([](nlohmann::json& d) { d["config"]["observation"]["sets"] = 64; },
                 {line_of([](nlohmann::json&) {}, "\"sets\""), "config.observation.sets", "more than 2^20 FACL rules"});
  expect_refused([](nlohmann::json& d) { d["config"]["speed"] = -3; }, {line_of([](nlohmann::json&) {}, "\"speed\""), "config.speed", "must be >= 0"});
  const auto extra = [](nlohmann::json& d) { d["config"]["observation"]["extra"] = 1; };
  expect_refused(extra, {line_of(extra, "\"extra\""), "config.observation.extra", "unknown key"});
  expect_refused([](nlohmann::json& d) { d.erase("channels"); }, {0, "channels", "missing"});
}

TEST_F(ExperimentBrokenPolicy, DeepNestingAndBrokenSyntaxAreRefusedWithTheirLine) {
  write_and_expect("{\n\"format\": \"peg3d-policy\",\n\"x\": " + std::string(100000, '[') + std::string(100000, ']') + "}",
                   {3, "", "nested more than 64 levels deep"});
  write_and_expect("{\n\"format\": \"peg3d-policy\",\n\"version\": 1,\n", {4, "", "not JSON"});
  write_and_expect("", {1, "", "not JSON"});
  write_and_expect(std::string("\x7f" "ELF\x02\x01\x01\0\0\0", 10), {1, "", "not JSON"});
}

}  // namespace
}  // namespace peg3d::experiment
