#include "core/config_overrides.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace peg3d::config {
namespace {

using nlohmann::json;

// The shape of a to_json image: nested sections, int/unsigned/float/bool/string leaves, arrays.
json sample_config() {
  json config;
  config["game"]["dt"] = 0.1;
  config["game"]["max_steps"] = 500;
  config["game"]["episodes"] = std::size_t{100};
  config["game"]["capture_radius"] = 1.0;
  config["learner"]["name"] = "facl";
  config["learner"]["greedy"] = false;
  config["learner"]["seeds"] = json::array({1, 2, 3});
  config["agents"] = json::array({json{{"speed", 1.0}}, json{{"speed", 2.0}}});
  config["optional_map"] = nullptr;
  return config;
}

std::string message_of(json& config, std::string_view assignment) {
  try {
    apply_override(config, assignment);
  } catch (const ConfigError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no ConfigError for " << assignment;
  return {};
}

bool contains(const std::string& text, std::string_view part) { return text.find(part) != std::string::npos; }

TEST(CoreConfigOverrides, SetsNestedFloat) {
  json config = sample_config();
  apply_override(config, "game.dt=0.05");
  EXPECT_EQ(config["game"]["dt"], 0.05);
  EXPECT_TRUE(config["game"]["dt"].is_number_float());
}

TEST(CoreConfigOverrides, IntegerIntoFloatLeafStaysFloat) {
  json config = sample_config();
  apply_override(config, "game.capture_radius=2");
  EXPECT_TRUE(config["game"]["capture_radius"].is_number_float());
  EXPECT_EQ(config["game"]["capture_radius"].get<double>(), 2.0);
}

TEST(CoreConfigOverrides, IntegralFloatIntoIntegerLeafBecomesInteger) {
  json config = sample_config();
  apply_override(config, "game.max_steps=1e3");
  EXPECT_TRUE(config["game"]["max_steps"].is_number_integer());
  EXPECT_EQ(config["game"]["max_steps"].get<int>(), 1000);
  apply_override(config, "game.max_steps=-20");
  EXPECT_EQ(config["game"]["max_steps"].get<int>(), -20);
}

TEST(CoreConfigOverrides, FractionIntoIntegerLeafIsRejected) {
  json config = sample_config();
  const std::string message = message_of(config, "game.max_steps=2.5");
  EXPECT_TRUE(contains(message, "'game.max_steps'")) << message;
  EXPECT_TRUE(contains(message, "expects an integer")) << message;
  EXPECT_EQ(config["game"]["max_steps"], 500);  // unchanged
}

TEST(CoreConfigOverrides, NegativeIntoUnsignedLeafIsRejected) {
  json config = sample_config();
  EXPECT_THROW(apply_override(config, "game.episodes=-1"), ConfigError);
  apply_override(config, "game.episodes=20");
  EXPECT_TRUE(config["game"]["episodes"].is_number_unsigned());
  EXPECT_EQ(config["game"]["episodes"].get<std::size_t>(), 20u);
}

TEST(CoreConfigOverrides, SetsBoolean) {
  json config = sample_config();
  apply_override(config, "learner.greedy=true");
  EXPECT_EQ(config["learner"]["greedy"], true);
  EXPECT_THROW(apply_override(config, "learner.greedy=yes"), ConfigError);
  EXPECT_THROW(apply_override(config, "learner.greedy=1"), ConfigError);
}

TEST(CoreConfigOverrides, StringLeafTakesTextVerbatim) {
  json config = sample_config();
  apply_override(config, "learner.name=q-learning");
  EXPECT_EQ(config["learner"]["name"], "q-learning");
  apply_override(config, "learner.name=123");  // parses as a number, but the leaf is a string
  EXPECT_EQ(config["learner"]["name"], "123");
  apply_override(config, "learner.name=\"a b\"");  // a JSON string is unquoted
  EXPECT_EQ(config["learner"]["name"], "a b");
  apply_override(config, "learner.name=");
  EXPECT_EQ(config["learner"]["name"], "");
}

TEST(CoreConfigOverrides, ReplacesArrayCheckingElementTypes) {
  json config = sample_config();
  apply_override(config, "learner.seeds=[7, 8]");
  EXPECT_EQ(config["learner"]["seeds"], json::array({7, 8}));
  EXPECT_THROW(apply_override(config, "learner.seeds=[1.5]"), ConfigError);
  EXPECT_THROW(apply_override(config, "learner.seeds=[1, \"x\"]"), ConfigError);
  EXPECT_THROW(apply_override(config, "learner.seeds=4"), ConfigError);
}

TEST(CoreConfigOverrides, AddressesArrayElementsByIndex) {
  json config = sample_config();
  apply_override(config, "agents.1.speed=3.5");
  EXPECT_EQ(config["agents"][1]["speed"], 3.5);
  const std::string message = message_of(config, "agents.2.speed=1");
  EXPECT_TRUE(contains(message, "valid indices under 'agents': 0..1")) << message;
}

TEST(CoreConfigOverrides, NullLeafAcceptsAnyValue) {
  json config = sample_config();
  apply_override(config, "optional_map=maps/forest.yaml");
  EXPECT_EQ(config["optional_map"], "maps/forest.yaml");
}

TEST(CoreConfigOverrides, UnknownKeyNamesKeyAndListsValidKeys) {
  json config = sample_config();
  const std::string message = message_of(config, "game.dtt=0.1");
  EXPECT_TRUE(contains(message, "'game.dtt'")) << message;
  EXPECT_TRUE(contains(message, "valid keys under 'game': capture_radius, dt, episodes, max_steps")) << message;

  const std::string top = message_of(config, "gmae.dt=0.1");
  EXPECT_TRUE(contains(top, "valid keys at the top level: agents, game, learner, optional_map")) << top;
}

TEST(CoreConfigOverrides, ConfigErrorCarriesTheKey) {
  json config = sample_config();
  try {
    apply_override(config, "game.nope=1");
    FAIL() << "no ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.key(), "game.nope");
  }
}

TEST(CoreConfigOverrides, MissingEqualsIsRejected) {
  json config = sample_config();
  const std::string message = message_of(config, "game.dt");
  EXPECT_TRUE(contains(message, "'game.dt'")) << message;
  EXPECT_TRUE(contains(message, "missing '='")) << message;
  EXPECT_TRUE(contains(message, "valid keys at the top level")) << message;
}

TEST(CoreConfigOverrides, EmptyKeySegmentIsRejected) {
  json config = sample_config();
  EXPECT_THROW(apply_override(config, "=1"), ConfigError);
  EXPECT_THROW(apply_override(config, "game..dt=1"), ConfigError);
  EXPECT_THROW(apply_override(config, "game.=1"), ConfigError);
}

TEST(CoreConfigOverrides, KeyBelowAValueIsRejected) {
  json config = sample_config();
  const std::string message = message_of(config, "game.dt.x=1");
  EXPECT_TRUE(contains(message, "'game.dt' is a number and has no key 'x'")) << message;
  EXPECT_TRUE(contains(message, "valid keys under 'game'")) << message;
}

TEST(CoreConfigOverrides, WholeSectionCannotBeReplaced) {
  json config = sample_config();
  const std::string message = message_of(config, "game={\"dt\": 1.0}");
  EXPECT_TRUE(contains(message, "is a section")) << message;
  EXPECT_TRUE(contains(message, "valid keys under 'game'")) << message;
}

TEST(CoreConfigOverrides, TypeMismatchNamesExpectedTypeAndLevel) {
  json config = sample_config();
  const std::string message = message_of(config, "game.dt=fast");
  EXPECT_TRUE(contains(message, "configuration key 'game.dt': expects a number (now 0.1), got 'fast'")) << message;
  EXPECT_TRUE(contains(message, "valid keys under 'game'")) << message;
}

TEST(CoreConfigOverrides, LaterOverridesWin) {
  json config = sample_config();
  const std::vector<std::string> sets = {"game.dt=0.2", "game.dt=0.3"};
  apply_overrides(config, sets);
  EXPECT_EQ(config["game"]["dt"], 0.3);
}

TEST(CoreConfigOverrides, FlattenListsSortedLeaves) {
  const std::vector<std::string> expected = {
      "agents.0.speed=1.0",
      "agents.1.speed=2.0",
      "game.capture_radius=1.0",
      "game.dt=0.1",
      "game.episodes=100",
      "game.max_steps=500",
      "learner.greedy=false",
      "learner.name=facl",
      "learner.seeds=[1,2,3]",
      "optional_map=null",
  };
  EXPECT_EQ(flatten(sample_config()), expected);
}

TEST(CoreConfigOverrides, FlattenQuotesOnlyStringsWithControlCharacters) {
  json config;
  config["a"] = "two\nlines";
  config["b"] = "x, y";
  config["c"] = json::object();
  config["d"] = json::array();
  const std::vector<std::string> expected = {"a=\"two\\nlines\"", "b=x, y", "c={}", "d=[]"};
  EXPECT_EQ(flatten(config), expected);
}

TEST(CoreConfigOverrides, FlattenedLinesApplyBack) {
  const json original = sample_config();
  json changed = original;
  apply_override(changed, "game.dt=9");
  apply_override(changed, "learner.name=other");
  apply_override(changed, "learner.seeds=[]");
  apply_override(changed, "agents.0.speed=5");
  for (const std::string& line : flatten(original)) apply_override(changed, line);
  EXPECT_EQ(changed, original);
}

}  // namespace
}  // namespace peg3d::config
