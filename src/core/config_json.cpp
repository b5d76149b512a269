#include "core/config_json.hpp"

#include <algorithm>
#include <limits>

#include <fmt/format.h>

namespace peg3d::config {

JsonReader::JsonReader(const nlohmann::json& in, std::string prefix, const ReadOptions& options)
    : in_(in), prefix_(std::move(prefix)), options_(options) {}

const nlohmann::json* JsonReader::take(const char* key) {
  taken_.emplace_back(key);
  const auto it = in_.find(key);
  if (it == in_.end()) {
    if (options_.complete) fail(key, "missing");
    return nullptr;
  }
  return &*it;
}

int ReadOptions::line_of(const std::string& field) const { return text.empty() ? 0 : json_line_of(text, field); }

void JsonReader::fail(const char* key, const std::string& message) const {
  throw ConfigError(options_.file, options_.line_of(field(key)), field(key), message);
}

void JsonReader::number(const char* key, double& v, Range, const char*, const char*) {
  const nlohmann::json* j = take(key);
  if (j == nullptr) return;
  if (!j->is_number()) fail(key, "expects a number, got " + brief(*j));
  v = j->get<double>();
}

void JsonReader::integer(const char* key, int& v, long long, long long, const char*, const char*) {
  const nlohmann::json* j = take(key);
  if (j == nullptr) return;
  constexpr double kMax = std::numeric_limits<int>::max(), kMin = std::numeric_limits<int>::min();
  if (j->is_number_integer() || j->is_number_unsigned()) {
    if (j->is_number_unsigned() ? j->get<std::uint64_t>() > static_cast<std::uint64_t>(kMax)
                                : (j->get<std::int64_t>() > kMax || j->get<std::int64_t>() < kMin)) {
      fail(key, "expects an integer that fits an int, got " + brief(*j));
    }
    v = j->get<int>();
    return;
  }
  // 3.0 is an integer written as a float; 2.5 is not, and is never truncated silently.
  if (j->is_number_float()) {
    const double d = j->get<double>();
    if (std::isfinite(d) && d == std::trunc(d) && d <= kMax && d >= kMin) {
      v = static_cast<int>(d);
      return;
    }
  }
  fail(key, "expects an integer, got " + brief(*j));
}

void JsonReader::flag(const char* key, bool& v, const char*) {
  const nlohmann::json* j = take(key);
  if (j == nullptr) return;
  if (!j->is_boolean()) fail(key, "expects true or false, got " + brief(*j));
  v = j->get<bool>();
}

void JsonReader::name(const char* key, std::string& v, const char* valid, const char*) {
  const nlohmann::json* j = take(key);
  if (j == nullptr) return;
  if (!j->is_string()) fail(key, std::string("expects a name (") + valid + "), got " + brief(*j));
  v = j->get<std::string>();
}

void JsonReader::names(const char* key, std::vector<std::string>& v, const char* valid, const char*) {
  const nlohmann::json* j = take(key);
  if (j == nullptr) return;
  if (!j->is_array()) fail(key, std::string("expects a list of names (") + valid + "), got " + brief(*j));
  // Bounded before anything is copied: a list of a million names is refused, not read.
  if (j->size() > kMaxNames) fail(key, fmt::format("lists {} names, at most {}", j->size(), kMaxNames));
  std::vector<std::string> out;
  for (std::size_t i = 0; i < j->size(); ++i) {
    if (!(*j)[i].is_string()) {
      const std::string element = field(key) + "." + std::to_string(i);
      throw ConfigError(options_.file, options_.line_of(element), element, std::string("expects a name (") + valid + ")");
    }
    out.push_back((*j)[i].get<std::string>());
  }
  v = std::move(out);
}

void JsonReader::finish() const {
  for (const auto& item : in_.items()) {
    if (std::find(taken_.begin(), taken_.end(), item.key()) != taken_.end()) continue;
    std::string valid;
    for (const auto& k : taken_) valid += (valid.empty() ? "" : ", ") + k;
    // A key is the user's text: a megabyte of it is named by its first 40 characters.
    const std::string& key = item.key();
    const std::string shown = key.size() <= 40 ? key : key.substr(0, 37) + "...";
    throw ConfigError(options_.file, options_.line_of(prefix_ + key), prefix_ + shown,
                      "unknown key (valid keys here: " + valid + ")");
  }
}

void FieldLister::number(const char* key, const double& v, Range r, const char* unit, const char* doc) {
  out_.push_back({prefix_ + key, "number", unit, r.text(), format_value(v), doc});
}

void FieldLister::integer(const char* key, const int& v, long long lo, long long hi, const char* unit,
                          const char* doc) {
  out_.push_back({prefix_ + key, "integer", unit, fmt::format("in [{}, {}]", lo, hi), std::to_string(v), doc});
}

void FieldLister::flag(const char* key, const bool& v, const char* doc) {
  out_.push_back({prefix_ + key, "flag", "", "true, false", v ? "true" : "false", doc});
}

void FieldLister::name(const char* key, const std::string& v, const char* valid, const char* doc) {
  out_.push_back({prefix_ + key, "name", "", valid, v, doc});
}

void FieldLister::names(const char* key, const std::vector<std::string>& v, const char* valid, const char* doc) {
  std::string list;
  for (const std::string& n : v) list += (list.empty() ? "" : ",") + n;
  out_.push_back({prefix_ + key, "names", "", valid, list.empty() ? "(none)" : list, doc});
}

std::string format_field_list(const std::vector<FieldInfo>& fields) {
  std::size_t key = 3, value = 5;
  for (const auto& f : fields) key = std::max(key, f.key.size()), value = std::max(value, f.value.size());
  std::string out = fmt::format("{:<{}}  {:<{}}  {:<6} {}\n", "key", key, "value", value, "unit", "valid values: meaning");
  for (const auto& f : fields) {
    out += fmt::format("{:<{}}  {:<{}}  {:<6} {}: {}\n", f.key, key, f.value, value, f.unit, f.valid, f.doc);
  }
  return out;
}

}  // namespace peg3d::config
