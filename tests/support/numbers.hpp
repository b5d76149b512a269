#pragma once

// Constants several test programs use, defined once: a unity build compiles a program's test files as one unit,
// where two files' own copies would collide.
#include <limits>

#include "geometry/angles.hpp"

namespace peg3d::testing {

inline constexpr double kDeg = kPi / 180.0;  // one degree, rad
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
inline constexpr double kInf = std::numeric_limits<double>::infinity();

}  // namespace peg3d::testing
