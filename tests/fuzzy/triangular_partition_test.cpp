#include "fuzzy/triangular_partition.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "core/validation.hpp"

namespace peg3d::fuzzy {
namespace {

TEST(TriangularPartition, MembershipsSumToOneOverTheWholeRange) {
  for (int sets : {2, 3, 5, 7}) {
    const TriangularPartition p(-3.14159, 3.14159, sets);
    for (int i = -100; i <= 1100; ++i) {  // also beyond the range: clamped
      const double x = -3.14159 + i * (2 * 3.14159) / 1000.0;
      double sum = 0.0;
      for (int k = 0; k < sets; ++k) sum += p.membership(k, x);
      ASSERT_NEAR(sum, 1.0, 1e-12) << "sets " << sets << " x " << x;
    }
  }
}

TEST(TriangularPartition, SetsPeakAtEvenlySpacedCenters) {
  const TriangularPartition p(0.0, 35.0, 5);
  for (int k = 0; k < 5; ++k) {
    EXPECT_DOUBLE_EQ(p.center(k), 8.75 * k);
    EXPECT_DOUBLE_EQ(p.membership(k, p.center(k)), 1.0);
  }
  EXPECT_DOUBLE_EQ(p.membership(1, 8.75 * 1.5), 0.5);
  EXPECT_DOUBLE_EQ(p.membership(3, 1.0), 0.0);
}

TEST(TriangularPartition, ActivationMatchesTheDenseMemberships) {
  const TriangularPartition p(0.0, 35.0, 5);
  for (double x : {-5.0, 0.0, 1.0, 8.75, 20.0, 34.999, 35.0, 50.0}) {
    const Activation a = p.activate(x);
    ASSERT_GE(a.lower, 0);
    ASSERT_LE(a.lower, 3);
    ASSERT_GE(a.t, 0.0);
    ASSERT_LE(a.t, 1.0);
    for (int k = 0; k < 5; ++k) {
      const double sparse = k == a.lower ? 1.0 - a.t : (k == a.lower + 1 ? a.t : 0.0);
      EXPECT_NEAR(sparse, p.membership(k, x), 1e-12) << "x " << x << " set " << k;
    }
  }
}

TEST(TriangularPartition, RejectsFewerThanTwoSetsAndEmptyRanges) {
  EXPECT_THROW(TriangularPartition(0.0, 1.0, 1, "distance"), InvalidParameter);
  EXPECT_THROW(TriangularPartition(1.0, 1.0, 5, "distance"), InvalidParameter);
  EXPECT_THROW(TriangularPartition(2.0, 1.0, 5, "distance"), InvalidParameter);
  EXPECT_THROW(TriangularPartition(0.0, std::nan(""), 5, "distance"), InvalidParameter);
  try {
    TriangularPartition(0.0, 1.0, 1, "pursuer.distance");
  } catch (const InvalidParameter& e) {
    EXPECT_NE(std::string(e.what()).find("pursuer.distance.sets"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace peg3d::fuzzy
