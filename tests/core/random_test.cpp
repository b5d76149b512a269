#include "core/random.hpp"

#include <set>

#include <gtest/gtest.h>

namespace peg3d {
namespace {

TEST(DeriveSeed, IsAPureFunctionOfRootAndPath) {
  EXPECT_EQ(derive_seed(42, {1, 2}), derive_seed(42, {1, 2}));
  static_assert(derive_seed(1, {2}) == derive_seed(1, {2}));
}

TEST(DeriveSeed, DistinctPathsAndRootsGiveDistinctSeeds) {
  std::set<std::uint64_t> seen;
  for (std::uint64_t root : {0ull, 1ull, 42ull})
    for (std::uint64_t a = 0; a < 20; ++a)
      for (std::uint64_t b = 0; b < 20; ++b) seen.insert(derive_seed(root, {a, b}));
  EXPECT_EQ(seen.size(), 3u * 20u * 20u);
  EXPECT_NE(derive_seed(7, {1, 2}), derive_seed(7, {2, 1}));  // order matters
  EXPECT_NE(derive_seed(7, {1}), derive_seed(7, {1, 0}));     // depth matters
}

}  // namespace
}  // namespace peg3d
