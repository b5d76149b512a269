#include "world/map/yaml_reader.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include <fmt/format.h>

#include "core/error.hpp"
#include "core/input_files.hpp"

namespace peg3d::world {
namespace {

using YAML::Node;

/// Levenshtein distance, to suggest the key a typo meant.
std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

std::string join(const std::vector<std::string_view>& items) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i > 0) out += ", ";
    out += items[i];
  }
  return out;
}

}  // namespace

using YAML::Node;

int line_of(const Node& n) {
  if (!n.IsDefined()) return 0;
  const int line = n.Mark().line;
  return line >= 0 ? line + 1 : 0;
}

std::string describe(const Node& n) {
  switch (n.Type()) {
    case YAML::NodeType::Null:
      return "nothing (an empty value)";
    case YAML::NodeType::Sequence:
      return "a list";
    case YAML::NodeType::Map:
      return "a mapping";
    case YAML::NodeType::Scalar:
      return fmt::format("\"{}\"", shown(n.Scalar()));
    default:
      return "an undefined value";
  }
}

void YamlReader::fail(int line, const std::string& field, const std::string& message) const {
  if (thrower_ != nullptr) thrower_(file_, line, field, message);
  throw InputError(file_, line, field, message);
}

YamlReader::Fields::Fields(const YamlReader& reader, const Node& node, std::string path)
    : reader_(reader), node_(node), path_(std::move(path)) {
  if (!node.IsMap()) reader.fail(node, path_, fmt::format("expected a mapping (key: value), got {}", describe(node)));
  for (auto it = node.begin(); it != node.end(); ++it) {
    const Node key = it->first;
    if (!key.IsScalar()) reader.fail(key, path_, "keys must be plain words");
    const std::string name = key.Scalar();
    for (const auto& e : entries_) {
      if (e.name == name) {
        reader.fail(key, field(shown(name)), fmt::format("duplicate key (first given at line {})", line_of(e.key)));
      }
    }
    // An empty value ("radius:") carries the mark of the next token: report it at its key instead.
    if (it->second.IsNull()) reader.fail(key, field(name), "has no value");
    entries_.push_back({name, key, it->second});
  }
}

void YamlReader::Fields::allow(const std::vector<std::string_view>& allowed) const {
  for (const auto& e : entries_) {
    if (std::find(allowed.begin(), allowed.end(), e.name) != allowed.end()) continue;
    std::string_view best;
    std::size_t best_distance = 3;  // suggest only close matches
    for (std::string_view a : allowed) {
      const std::size_t d = edit_distance(e.name, a);
      if (d < best_distance) best_distance = d, best = a;
    }
    const std::string hint = best.empty() ? "" : fmt::format("; did you mean '{}'?", best);
    reader_.fail(e.key, field(shown(e.name)), fmt::format("unknown key (allowed: {}){}", join(allowed), hint));
  }
}

const Node* YamlReader::Fields::find(std::string_view name) const {
  for (const auto& e : entries_) {
    if (e.name == name) return &e.value;
  }
  return nullptr;
}

const Node& YamlReader::Fields::need(std::string_view name) const {
  if (const Node* n = find(name)) return *n;
  reader_.fail(node_, field(name), "missing required field");
}

double YamlReader::number(const Node& n, const std::string& field) const {
  if (!n.IsScalar() || n.Tag() == "!") fail(n, field, fmt::format("expected a number, got {}", describe(n)));
  double v = 0.0;
  if (!YAML::convert<double>::decode(n, v)) fail(n, field, fmt::format("expected a number, got {}", describe(n)));
  if (!std::isfinite(v)) fail(n, field, fmt::format("must be a finite number, got {}", shown(n.Scalar())));
  return v;
}

double YamlReader::positive(const Node& n, const std::string& field) const {
  const double v = number(n, field);
  if (!(v > 0.0)) fail(n, field, fmt::format("must be > 0, got {}", v));
  return v;
}

double YamlReader::non_negative(const Node& n, const std::string& field) const {
  const double v = number(n, field);
  if (!(v >= 0.0)) fail(n, field, fmt::format("must be >= 0, got {}", v));
  return v;
}

long long YamlReader::integer(const Node& n, const std::string& field) const {
  long long v = 0;
  if (!n.IsScalar() || n.Tag() == "!" || !YAML::convert<long long>::decode(n, v)) {
    fail(n, field, fmt::format("expected an integer, got {}", describe(n)));
  }
  return v;
}

std::uint64_t YamlReader::unsigned_integer(const Node& n, const std::string& field) const {
  unsigned long long v = 0;
  if (!n.IsScalar() || n.Tag() == "!" || !YAML::convert<unsigned long long>::decode(n, v)) {
    fail(n, field, fmt::format("expected a non-negative integer, got {}", describe(n)));
  }
  return v;
}

bool YamlReader::boolean(const Node& n, const std::string& field) const {
  bool v = false;
  if (!n.IsScalar() || n.Tag() == "!" || !YAML::convert<bool>::decode(n, v)) {
    fail(n, field, fmt::format("expected true or false, got {}", describe(n)));
  }
  return v;
}

std::string YamlReader::text(const Node& n, const std::string& field) const {
  if (!n.IsScalar() || n.Scalar().empty()) fail(n, field, fmt::format("expected a string, got {}", describe(n)));
  return n.Scalar();
}

Vec3 YamlReader::vec3(const Node& n, const std::string& field) const {
  if (!n.IsSequence() || n.size() != 3) {
    fail(n, field, fmt::format("expected a list of 3 numbers [x, y, z], got {}",
                               n.IsSequence() ? fmt::format("a list of {}", n.size()) : describe(n)));
  }
  Vec3 v;
  for (int i = 0; i < 3; ++i) v[i] = number(n[i], fmt::format("{}[{}]", field, i));
  return v;
}

std::pair<double, double> YamlReader::positive_range(const Node& n, const std::string& field) const {
  if (n.IsScalar()) {
    const double v = positive(n, field);
    return {v, v};
  }
  if (!n.IsSequence() || n.size() != 2) {
    fail(n, field, fmt::format("expected a number or a list [min, max], got {}", describe(n)));
  }
  const double lo = positive(n[0], field + "[0]");
  const double hi = positive(n[1], field + "[1]");
  if (hi < lo) fail(n, field, fmt::format("min {} is larger than max {}", lo, hi));
  return {lo, hi};
}

const Node& YamlReader::sequence(const Node& n, const std::string& field) const {
  if (!n.IsSequence()) fail(n, field, fmt::format("expected a list, got {}", describe(n)));
  return n;
}

Node YamlReader::node_of(const Fields& f, const std::string& relative) const {
  Node node = f.node();
  std::size_t start = 0;
  while (start < relative.size()) {
    const std::size_t dot = std::min(relative.find('.', start), relative.size());
    std::string part = relative.substr(start, dot - start);
    int index = -1;
    if (const std::size_t b = part.find('['); b != std::string::npos) {
      index = std::atoi(part.c_str() + b + 1);
      part = part.substr(0, b);
    }
    if (!part.empty()) {
      if (!node.IsMap() || !node[part]) return f.node();
      node = node[part];
    }
    if (index >= 0) {
      if (!node.IsSequence() || index >= static_cast<int>(node.size())) return f.node();
      node = node[static_cast<std::size_t>(index)];
    }
    start = dot + 1;
  }
  return node;
}

}  // namespace peg3d::world
