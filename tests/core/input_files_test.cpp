#include "core/input_files.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.hpp"
#include "core/yaml_input.hpp"
#include "support/input_error_of.hpp"
#include "support/scratch_dir.hpp"

namespace peg3d {
namespace {

using peg3d::testing::input_error_of;

namespace fs = std::filesystem;

class CoreInputFiles : public ::testing::Test {
 protected:
  fs::path write(const std::string& name, const std::string& text) {
    const fs::path p = dir_ / name;
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }
  peg3d::testing::ScratchDir scratch_;  // before dir_, which copies its path
  fs::path dir_ = scratch_.path();
};

TEST_F(CoreInputFiles, ReadsARegularFileWhole) {
  const std::string text("a\0b\nc", 5);
  EXPECT_EQ(read_input_file(write("f.txt", text), "map file"), text);
}

TEST_F(CoreInputFiles, RefusesMissingFilesDirectoriesDevicesAndFifos) {
  EXPECT_EQ(input_error_of([&] { read_input_file(dir_ / "none.yaml", "map file"); }).message(), "map file not found");
  EXPECT_EQ(input_error_of([&] { read_input_file(dir_, "map file"); }).message(), "map file is not a regular file");
  // /dev/zero never ends and a FIFO without a writer blocks forever: both are refused before any read.
  EXPECT_EQ(input_error_of([&] { read_input_file("/dev/zero", "policy file"); }).message(), "policy file is not a regular file");
  const fs::path fifo = dir_ / "fifo.json";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(input_error_of([&] { read_input_file(fifo, "configuration"); }).message(), "configuration is not a regular file");
}

TEST_F(CoreInputFiles, RefusesFilesAboveTheSizeCap) {
  const fs::path f = write("big.json", std::string(1001, ' '));
  EXPECT_EQ(read_input_file(f, "x", 1001).size(), 1001u);
  const InputError e = input_error_of([&] { read_input_file(f, "policy file", 1000); });
  EXPECT_EQ(e.file(), f);
  EXPECT_EQ(e.message(), "policy file is 1001 bytes, more than the 1000 this build reads");
}

TEST(CoreJsonText, NestingBeyondTheLimitIsRefusedWithItsLine) {
  const std::string ok = std::string(kMaxNestingDepth, '[') + std::string(kMaxNestingDepth, ']');
  EXPECT_NO_THROW(parse_json_text(ok, "ok.json"));
  // A hundred thousand levels: nlohmann's destructor and dump recurse, so this crashed before the pre-scan.
  const std::string deep = "{\n\"a\":\n" + std::string(100000, '[') + std::string(100000, ']') + "}";
  try {
    parse_json_text(deep, "deep.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 3);
    EXPECT_EQ(e.message(), "nested more than 64 levels deep");
  }
  // Brackets inside strings are text, not nesting.
  EXPECT_NO_THROW(parse_json_text("{\"a\": \"" + std::string(1000, '[') + "\\\"\"}", "s.json"));
}

TEST(CoreJsonText, SyntaxErrorsNameTheirLine) {
  try {
    parse_json_text("{\n  \"a\": 1,\n  \"b\": ]\n}", "x.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "x.json");
    EXPECT_EQ(e.line(), 3);
    EXPECT_EQ(e.message().rfind("not JSON: ", 0), 0u) << e.message();
  }
}

TEST(CoreJsonText, LineOfAFieldFollowsKeysIndicesAndNestedLists) {
  const std::string text =
      "{\n"
      "  \"pursuer\": {\"speed\": 1,\n"
      "    \"name\": \"x]}\\\"{\"},\n"
      "  \"channels\": [\n"
      "    {\"actor\": [1,\n"
      "       2,\n"
      "       3]},\n"
      "    {\"actor\": [[1], {\"k\": 2},\n"
      "       4]}\n"
      "  ],\n"
      "  \"list\": [0, 1,\n 2]\n"
      "}\n";
  EXPECT_EQ(json_line_of(text, "pursuer"), 2);
  EXPECT_EQ(json_line_of(text, "pursuer.speed"), 2);
  EXPECT_EQ(json_line_of(text, "pursuer.name"), 3);
  EXPECT_EQ(json_line_of(text, "channels"), 4);
  EXPECT_EQ(json_line_of(text, "channels[0].actor"), 5);
  EXPECT_EQ(json_line_of(text, "channels[0].actor[2]"), 7);
  EXPECT_EQ(json_line_of(text, "channels[1].actor[2]"), 9);
  EXPECT_EQ(json_line_of(text, "list.2"), 12);  // the --set form of an index
  EXPECT_EQ(json_line_of(text, "channels[2]"), 0);
  EXPECT_EQ(json_line_of(text, "evader.speed"), 0);
  EXPECT_EQ(json_line_of(text, ""), 0);
}

TEST(CoreJsonText, BriefShortensLongValues) {
  EXPECT_EQ(brief(nlohmann::json(2.5)), "2.5");
  EXPECT_EQ(brief(nlohmann::json(std::string(1000, 'x'))), "\"" + std::string(36, 'x') + "...");
  EXPECT_EQ(brief(nlohmann::json(std::vector<int>(100, 1))), "a list of 100 items");
  EXPECT_LE(brief(nlohmann::json::parse("{\"a\": \"" + std::string(500, 'y') + "\"}")).size(), 40u);
}

TEST(CoreYamlText, DeepNestingIsAnErrorNotACrash) {
  const std::string deep = "a:\n  " + std::string(100000, '[') + std::string(100000, ']') + "\n";
  try {
    parse_yaml_text(deep, "deep.yaml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "deep.yaml");
    EXPECT_NE(e.message().find("nested too deeply"), std::string::npos) << e.what();
  }
  try {
    parse_yaml_text("a: [1, 2\nb: 3\n", "bad.yaml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_GT(e.line(), 0);
    EXPECT_NE(e.message().find("YAML syntax error"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace peg3d
