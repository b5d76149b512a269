#pragma once
// Reading a YAML document a user wrote, field by field: typed readers that check each value's YAML type and
// range, and mappings whose keys are checked (a duplicate, an unknown key with the nearest allowed one as a
// hint, a missing required field). Every failure names the file, the line and the field, a dotted path such
// as "movers[2].path.speed"; a reader throws InputError, or its own kind of InputError (fail()).

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "geometry/vector.hpp"

namespace peg3d::world {

/// The 1-based line of a node (0 when it has none).
int line_of(const YAML::Node& n);
/// A node as a message names it: "a list", "a mapping", "\"text\"", ...
std::string describe(const YAML::Node& n);

/// Throws an `Error` (InputError or one of its kinds) naming the file, line and field.
template <class Error>
[[noreturn]] void throw_error(const std::filesystem::path& file, int line, const std::string& field,
                              const std::string& message) {
  throw Error(file, line, field, message);
}

class YamlReader {
 public:
  using Thrower = void (*)(const std::filesystem::path&, int, const std::string&, const std::string&);

  /// A reader of `file` whose failures `thrower` throws (InputError when null).
  explicit YamlReader(std::filesystem::path file, Thrower thrower = nullptr) : file_(std::move(file)), thrower_(thrower) {}

  const std::filesystem::path& file() const { return file_; }

  /// Throws this reader's error naming the file, `line` and `field`.
  [[noreturn]] void fail(int line, const std::string& field, const std::string& message) const;
  [[noreturn]] void fail(const YAML::Node& at, const std::string& field, const std::string& message) const {
    fail(line_of(at), field, message);
  }

  /// A YAML mapping whose keys are checked: duplicates and (after allow()) unknown keys are errors.
  class Fields {
   public:
    Fields(const YamlReader& reader, const YAML::Node& node, std::string path);
    /// Rejects keys not in `allowed`, suggesting the nearest allowed one.
    void allow(const std::vector<std::string_view>& allowed) const;
    const YAML::Node* find(std::string_view name) const;
    const YAML::Node& need(std::string_view name) const;
    std::string field(std::string_view name) const {
      return path_.empty() ? std::string(name) : path_ + "." + std::string(name);
    }
    const YAML::Node& node() const { return node_; }
    const std::string& path() const { return path_; }

   private:
    struct Entry {
      std::string name;
      YAML::Node key;
      YAML::Node value;
    };
    const YamlReader& reader_;
    YAML::Node node_;
    std::string path_;
    std::vector<Entry> entries_;
  };

  // Typed readers: each checks the YAML type and the value and fails with the field's name.
  double number(const YAML::Node& n, const std::string& field) const;
  double positive(const YAML::Node& n, const std::string& field) const;
  double non_negative(const YAML::Node& n, const std::string& field) const;
  long long integer(const YAML::Node& n, const std::string& field) const;
  std::uint64_t unsigned_integer(const YAML::Node& n, const std::string& field) const;
  bool boolean(const YAML::Node& n, const std::string& field) const;
  std::string text(const YAML::Node& n, const std::string& field) const;
  Vec3 vec3(const YAML::Node& n, const std::string& field) const;
  /// A positive range: a single number r (meaning [r, r]) or [min, max] with 0 < min <= max.
  std::pair<double, double> positive_range(const YAML::Node& n, const std::string& field) const;
  const YAML::Node& sequence(const YAML::Node& n, const std::string& field) const;

  /// The node of a field below a mapping, given relative to it ("path.speed", "size[1]"); the mapping itself
  /// when the field is empty or not there (so an error always has a line).
  YAML::Node node_of(const Fields& f, const std::string& relative) const;

 private:
  std::filesystem::path file_;
  Thrower thrower_;
};

}  // namespace peg3d::world
