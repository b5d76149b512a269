#include "core/config_fields.hpp"

#include <cmath>

#include <fmt/format.h>

namespace peg3d::config {

bool is_name(std::string_view text) {
  if (text.empty() || text.size() > kMaxNameLength) return false;
  for (const char c : text) {
    if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' || c == '_')) return false;
  }
  return true;
}

bool Range::contains(double v) const {
  if (!std::isfinite(v)) return false;
  const bool above = lo_open ? v > lo : v >= lo;
  const bool below = hi_open ? v < hi : v <= hi;
  return above && below;
}

std::string Range::text() const {
  const bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
  if (!has_lo && !has_hi) return "finite";
  if (!has_hi) return fmt::format("{} {}", lo_open ? ">" : ">=", format_value(lo));
  if (!has_lo) return fmt::format("{} {}", hi_open ? "<" : "<=", format_value(hi));
  return fmt::format("in {}{}, {}{}", lo_open ? '(' : '[', format_value(lo), format_value(hi), hi_open ? ')' : ']');
}

void Validator::number(const char* key, const double& value, Range range, const char*, const char*) {
  if (!std::isfinite(value)) throw InvalidParameter(field(key), format_value(value), "must be finite");
  if (!range.contains(value)) throw InvalidParameter(field(key), format_value(value), "must be " + range.text());
}

void Validator::integer(const char* key, const int& value, long long lo, long long hi, const char*, const char*) {
  if (value < lo || value > hi) {
    throw InvalidParameter(field(key), std::to_string(value), fmt::format("must lie in [{}, {}]", lo, hi));
  }
}

void Validator::name(const char* key, const std::string& value, const char* valid, const char*) {
  if (!is_name(value)) {
    const std::string shown = value.size() <= 40 ? value : value.substr(0, 37) + "...";
    throw InvalidParameter(field(key), "\"" + shown + "\"",
                           fmt::format("must be a name of 1 to {} characters a-z, 0-9, - and _: {}", kMaxNameLength, valid));
  }
}

void Validator::names(const char* key, const std::vector<std::string>& value, const char* valid, const char* doc) {
  if (value.size() > kMaxNames) {
    throw InvalidParameter(field(key), fmt::format("{} names", value.size()), fmt::format("must list at most {}", kMaxNames));
  }
  for (std::size_t i = 0; i < value.size(); ++i) name((std::string(key) + "." + std::to_string(i)).c_str(), value[i], valid, doc);
}

void Validator::require(bool ok, std::string_view key, double value, const char* requirement) const {
  if (!ok) throw InvalidParameter(field(key), format_value(value), requirement);
}

void Validator::require(bool ok, std::string_view key, std::string_view value, const char* requirement) const {
  if (!ok) throw InvalidParameter(field(key), value, requirement);
}

}  // namespace peg3d::config
