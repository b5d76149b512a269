// StepProfile (core/step_profile.hpp): a scope counts its time to its part, and a scope opened within another
// counts only to its own part, the enclosing one getting its time less the inner one's.
#include "core/step_profile.hpp"

#include <gtest/gtest.h>

namespace peg3d {
namespace {

// Spins until `ticks` time-stamp ticks have passed.
void spin(std::uint64_t ticks) {
  for (const std::uint64_t start = StepProfile::now(); StepProfile::now() - start < ticks;) {
  }
}

TEST(CoreStepProfile, AScopeWithinAnotherCountsOnlyToItsOwnPart) {
  StepProfile profile;
  StepProfile::current() = &profile;
  const std::uint64_t before = StepProfile::now();
  {
    const StepProfile::Scope outer(StepProfile::kObservation);
    spin(200000);
    {
      const StepProfile::Scope inner(StepProfile::kMapQuery);
      spin(4000000);
    }
    spin(200000);
  }
  const std::uint64_t after = StepProfile::now();
  StepProfile::current() = nullptr;
  const std::uint64_t outer = profile.ticks[StepProfile::kObservation], inner = profile.ticks[StepProfile::kMapQuery];
  EXPECT_GE(inner, 4000000u);
  EXPECT_GE(outer, 400000u);
  // The outer part holds its own spins, not the inner one's (ten times as long).
  EXPECT_LT(outer, inner / 2);
  EXPECT_LE(outer + inner, after - before);
  // Without a profile, nothing is recorded.
  {
    const StepProfile::Scope unrecorded(StepProfile::kSensing);
    spin(1000);
  }
  EXPECT_EQ(profile.ticks[StepProfile::kSensing], 0u);
}

}  // namespace
}  // namespace peg3d
