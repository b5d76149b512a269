#include "core/validation.hpp"

#include <cmath>
#include <fmt/format.h>

namespace peg3d {

InvalidParameter::InvalidParameter(std::string_view name, std::string_view value, std::string_view requirement)
    : InputError(Preformatted{}, fmt::format("invalid parameter '{}' = {}: {}", name, value, requirement), {}, 0,
                 std::string(name)),
      name_(name) {}

std::string format_value(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  return fmt::format("{}", value);
}

void require_finite(std::string_view name, double value) {
  if (!std::isfinite(value)) throw InvalidParameter(name, format_value(value), "must be finite");
}

void require_positive(std::string_view name, double value) {
  require_finite(name, value);
  if (!(value > 0.0)) throw InvalidParameter(name, format_value(value), "must be > 0");
}

void require_non_negative(std::string_view name, double value) {
  require_finite(name, value);
  if (!(value >= 0.0)) throw InvalidParameter(name, format_value(value), "must be >= 0");
}

void require_in_range(std::string_view name, double value, double lo, double hi, bool lo_open, bool hi_open) {
  require_finite(name, value);
  const bool above = lo_open ? value > lo : value >= lo;
  const bool below = hi_open ? value < hi : value <= hi;
  if (!above || !below) {
    throw InvalidParameter(name, format_value(value),
                           fmt::format("must lie in {}{}, {}{}", lo_open ? '(' : '[', format_value(lo),
                                       format_value(hi), hi_open ? ')' : ']'));
  }
}

void require_at_least(std::string_view name, long long value, long long min_count) {
  if (value < min_count) throw InvalidParameter(name, std::to_string(value), fmt::format("must be >= {}", min_count));
}

void require_range(std::string_view name, double lo, double hi) {
  if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo < hi)) {
    throw InvalidParameter(name, fmt::format("[{}, {}]", format_value(lo), format_value(hi)),
                           "must be a finite, non-empty range (lo < hi)");
  }
}

}  // namespace peg3d
