#include "core/validation.hpp"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace peg3d {
namespace {

std::string message_of(auto&& f) {
  try {
    f();
  } catch (const InvalidParameter& e) {
    return e.what();
  }
  return "";
}

TEST(Validation, MessageNamesParameterAndValue) {
  const std::string m = message_of([] { require_positive("agent.speed", -1.5); });
  EXPECT_NE(m.find("agent.speed"), std::string::npos) << m;
  EXPECT_NE(m.find("-1.5"), std::string::npos) << m;
}

TEST(Validation, RejectsNanAndInfinity) {
  EXPECT_NE(message_of([] { require_finite("x", std::nan("")); }).find("nan"), std::string::npos);
  EXPECT_NE(message_of([] { require_positive("x", std::numeric_limits<double>::infinity()); }).find("inf"),
            std::string::npos);
}

TEST(Validation, RangeRespectsOpenAndClosedEnds) {
  EXPECT_NO_THROW(require_in_range("r", 1.0, 0.0, 1.0, true, false));
  EXPECT_THROW(require_in_range("r", 0.0, 0.0, 1.0, true, false), InvalidParameter);
  EXPECT_THROW(require_in_range("r", 1.0, 0.0, 1.0, false, true), InvalidParameter);
  EXPECT_NE(message_of([] { require_in_range("r", 2.0, 0.0, 1.0, true); }).find("(0, 1]"), std::string::npos);
}

TEST(Validation, RejectsEmptyRangeAndTooFewItems) {
  EXPECT_NE(message_of([] { require_range("input.range", 3.0, 3.0); }).find("input.range"), std::string::npos);
  EXPECT_NE(message_of([] { require_at_least("sets", 1, 2); }).find("sets"), std::string::npos);
}

}  // namespace
}  // namespace peg3d
