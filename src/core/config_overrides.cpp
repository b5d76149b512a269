#include "core/config_overrides.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <fmt/format.h>
#include <limits>
#include <optional>
#include <utility>

namespace peg3d::config {

using nlohmann::json;

namespace {
// Overrides come from the command line: no file, the key as the field, and the message says it all.
ConfigError override_error(const std::string& key, const std::string& message) {
  return ConfigError(InputError::Preformatted{}, message, std::filesystem::path(), 0, key);
}
}  // namespace

namespace {

// What the user can type at `node`, for error messages: its keys, or the index range of an array.
std::string describe_level(const json& node, std::string_view path) {
  const std::string where = path.empty() ? std::string("at the top level") : fmt::format("under '{}'", path);
  if (node.is_array()) {
    if (node.empty()) return fmt::format("the array {} is empty", where);
    return fmt::format("valid indices {}: 0..{}", where, node.size() - 1);
  }
  if (!node.is_object() || node.empty()) return fmt::format("there are no keys {}", where);
  std::string keys;
  for (const auto& item : node.items()) keys += (keys.empty() ? "" : ", ") + item.key();
  return fmt::format("valid keys {}: {}", where, keys);
}

[[noreturn]] void fail(const std::string& key, std::string_view problem, const json& level,
                       std::string_view level_path) {
  throw override_error(key,
                    fmt::format("configuration key '{}': {}; {}", key, problem, describe_level(level, level_path)));
}

std::string_view kind(const json& j) {
  switch (j.type()) {
    case json::value_t::number_integer: return "an integer";
    case json::value_t::number_unsigned: return "a non-negative integer";
    case json::value_t::number_float: return "a number";
    case json::value_t::boolean: return "true or false";
    case json::value_t::string: return "a string";
    case json::value_t::array: return "an array";
    case json::value_t::object: return "a section";
    default: return "null";
  }
}

std::optional<std::size_t> parse_index(std::string_view text) {
  std::size_t index = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), index);
  if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return index;
}

// `value` converted to the JSON type of `old`, or nullopt when they are incompatible.
std::optional<json> coerce(const json& old, const json& value) {
  switch (old.type()) {
    case json::value_t::null: return value;
    case json::value_t::boolean:
    case json::value_t::string:
      if (value.type() == old.type()) return value;
      return std::nullopt;
    case json::value_t::number_float:
      if (value.is_number()) return json(value.get<double>());
      return std::nullopt;
    case json::value_t::number_integer:
    case json::value_t::number_unsigned: {
      const bool is_unsigned = old.is_number_unsigned();
      if (value.is_number_unsigned()) {
        const auto v = value.get<std::uint64_t>();
        if (is_unsigned) return json(v);
        if (v > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())) return std::nullopt;
        return json(static_cast<std::int64_t>(v));
      }
      if (value.is_number_integer()) {
        const auto v = value.get<std::int64_t>();
        if (is_unsigned && v < 0) return std::nullopt;
        return is_unsigned ? json(static_cast<std::uint64_t>(v)) : json(v);
      }
      if (value.is_number_float()) {
        // 2.0 and 1e3 are integers written as floats; 2.5 is not, and must not be truncated silently.
        const double v = value.get<double>();
        if (!std::isfinite(v) || v != std::trunc(v)) return std::nullopt;
        if (is_unsigned) {
          if (v < 0.0 || v >= 0x1p64) return std::nullopt;
          return json(static_cast<std::uint64_t>(v));
        }
        if (v < -0x1p63 || v >= 0x1p63) return std::nullopt;
        return json(static_cast<std::int64_t>(v));
      }
      return std::nullopt;
    }
    case json::value_t::array: {
      if (!value.is_array()) return std::nullopt;
      if (old.empty()) return value;
      json converted = json::array();
      for (const json& element : value) {
        std::optional<json> c = coerce(old.front(), element);
        if (!c) return std::nullopt;
        converted.push_back(std::move(*c));
      }
      return converted;
    }
    default: return std::nullopt;  // objects are rejected before; binary values are never config
  }
}

bool has_control_character(std::string_view text) {
  return std::any_of(text.begin(), text.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20; });
}

std::string leaf_text(const json& leaf) {
  if (leaf.is_string()) {
    const auto& text = leaf.get_ref<const std::string&>();
    return has_control_character(text) ? leaf.dump() : text;
  }
  return leaf.dump();
}

void flatten_into(const json& node, const std::string& prefix, std::vector<std::pair<std::string, std::string>>& out) {
  const auto child = [&prefix](std::string_view key) {
    return prefix.empty() ? std::string(key) : fmt::format("{}.{}", prefix, key);
  };
  if (node.is_object()) {
    if (node.empty() && !prefix.empty()) out.emplace_back(prefix, "{}");
    for (const auto& item : node.items()) flatten_into(item.value(), child(item.key()), out);
    return;
  }
  if (node.is_array()) {
    const bool nested =
        std::any_of(node.begin(), node.end(), [](const json& e) { return e.is_object() || e.is_array(); });
    if (nested) {
      for (std::size_t i = 0; i < node.size(); ++i) flatten_into(node[i], child(std::to_string(i)), out);
      return;
    }
  }
  out.emplace_back(prefix, leaf_text(node));
}

}  // namespace

void apply_override(json& config, std::string_view assignment) {
  const std::size_t eq = assignment.find('=');
  if (!config.is_object()) {
    throw override_error(std::string(assignment.substr(0, eq)), "configuration overrides need a JSON object to apply to");
  }
  if (eq == std::string_view::npos) {
    const std::string whole(assignment);
    throw override_error(whole, fmt::format("configuration override '{}': missing '=' (expected key=value); {}", whole,
                                         describe_level(config, "")));
  }
  const std::string key(assignment.substr(0, eq));
  const std::string_view text = assignment.substr(eq + 1);

  // Walk to the leaf; `level` and `level_path` stay one step behind for the error messages.
  json* node = &config;
  const json* level = &config;
  std::string level_path;
  std::string path;
  for (std::size_t start = 0; start <= key.size();) {
    const std::size_t dot = std::min(key.find('.', start), key.size());
    const std::string_view segment = std::string_view(key).substr(start, dot - start);
    if (segment.empty()) fail(key, "empty key segment", *node, path);
    if (node->is_object()) {
      const auto it = node->find(segment);
      if (it == node->end()) fail(key, fmt::format("unknown key '{}'", segment), *node, path);
      level = node;
      node = &*it;
    } else if (node->is_array()) {
      const std::optional<std::size_t> index = parse_index(segment);
      if (!index || *index >= node->size()) fail(key, fmt::format("'{}' is not an index", segment), *node, path);
      level = node;
      node = &(*node)[*index];
    } else {
      fail(key, fmt::format("'{}' is {} and has no key '{}'", path, kind(*node), segment), *level, level_path);
    }
    level_path = path;
    path = path.empty() ? std::string(segment) : fmt::format("{}.{}", path, segment);
    start = dot + 1;
  }

  if (node->is_object()) {
    fail(key, "is a section, not a value: set its keys one by one", *node, path);
  }

  json parsed = json::parse(text, nullptr, /*allow_exceptions=*/false);
  const bool names = node->is_array() && (node->empty() || node->front().is_string());
  if (names && !parsed.is_array()) {
    // A list of names (players): "flee,random" as ["flee", "random"]; "" empties it.
    parsed = json::array();
    for (std::size_t start = 0; start < text.size();) {
      const std::size_t comma = std::min(text.find(',', start), text.size());
      parsed.push_back(std::string(text.substr(start, comma - start)));
      start = comma + 1;
    }
  } else if (parsed.is_discarded() || (node->is_string() && !parsed.is_string())) {
    // Text that is not JSON is a string; into a string leaf, any text that is not a JSON string is verbatim.
    parsed = std::string(text);
  }

  std::optional<json> value = coerce(*node, parsed);
  if (!value) {
    fail(key, fmt::format("expects {} (now {}), got '{}'", kind(*node), leaf_text(*node), text), *level, level_path);
  }
  *node = std::move(*value);
}

void apply_overrides(json& config, std::span<const std::string> assignments) {
  for (const std::string& assignment : assignments) apply_override(config, assignment);
}

std::vector<std::string> flatten(const json& config) {
  std::vector<std::pair<std::string, std::string>> leaves;
  flatten_into(config, "", leaves);
  std::stable_sort(leaves.begin(), leaves.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<std::string> lines;
  lines.reserve(leaves.size());
  for (const auto& [key, value] : leaves) lines.push_back(fmt::format("{}={}", key, value));
  return lines;
}

}  // namespace peg3d::config
