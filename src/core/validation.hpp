#pragma once
// Parameter validation at the boundary. Every check throws InvalidParameter whose message names the
// parameter and the offending value; inside hot loops use assertions instead.

#include <string>
#include <string_view>

#include "core/error.hpp"

namespace peg3d {

/// Thrown when a configuration value is out of its valid range. what() names the parameter and value; field()
/// and parameter() are the parameter's dotted name.
class InvalidParameter : public InputError {
 public:
  InvalidParameter(std::string_view name, std::string_view value, std::string_view requirement);
  const std::string& parameter() const noexcept { return name_; }

 private:
  std::string name_;
};

/// Formats a double the way messages print it ("nan", "inf", "0.1", "1e-12").
std::string format_value(double value);

/// value must be finite (not NaN, not infinite).
void require_finite(std::string_view name, double value);
/// value must be finite and > 0.
void require_positive(std::string_view name, double value);
/// value must be finite and >= 0.
void require_non_negative(std::string_view name, double value);
/// value must be finite and lie in the interval; open ends exclude the bound.
void require_in_range(std::string_view name, double value, double lo, double hi, bool lo_open = false,
                      bool hi_open = false);
/// An integer count must be at least min_count.
void require_at_least(std::string_view name, long long value, long long min_count);
/// lo < hi, both finite: a non-empty range. Names the pair as "name".
void require_range(std::string_view name, double lo, double hi);

}  // namespace peg3d
