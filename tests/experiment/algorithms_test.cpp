// The algorithms of a comparison (experiment/algorithms.hpp): presets, named variants of a preset, and the
// `--set` overrides that reach one algorithm or all of them.
#include <gtest/gtest.h>

#include "core/config_json.hpp"
#include "core/validation.hpp"
#include "experiment/algorithms.hpp"

namespace peg3d::experiment {
namespace {

TEST(Algorithms, APresetEntersUnderItsOwnName) {
  const auto algs = make_algorithms({"peg3d", "robust"}, {});
  ASSERT_EQ(algs.size(), 2u);
  EXPECT_EQ(algs[0].name, "peg3d");
  EXPECT_EQ(algs[1].name, "robust");
  EXPECT_EQ(config::to_json(algs[1].config), config::to_json(trial_preset("robust")));
}

TEST(Algorithms, ANamedVariantEntersAPresetTwiceAndTakesOnlyItsOwnOverrides) {
  const auto algs = make_algorithms({"robust", "sensing=robust"},
                                    {"sensing.pursuer.lidar.azimuth_rays=16", "time_limit=50"});
  ASSERT_EQ(algs.size(), 2u);
  EXPECT_EQ(algs[1].name, "sensing");
  EXPECT_EQ(algs[0].config.game.pursuer.sensors.lidar.azimuth_rays, 0);
  EXPECT_EQ(algs[1].config.game.pursuer.sensors.lidar.azimuth_rays, 16);
  EXPECT_EQ(algs[0].config.game.time_limit, 50.0);
  EXPECT_EQ(algs[1].config.game.time_limit, 50.0);
  // Apart from its own override, the variant is its preset.
  TrialConfig back = algs[1].config;
  back.game.pursuer.sensors.lidar.azimuth_rays = 0;
  EXPECT_EQ(config::to_json(back), config::to_json(algs[0].config));
}

TEST(Algorithms, NamesMustBeUsableAndUnique) {
  EXPECT_THROW(make_algorithms({"robust", "robust"}, {}), InputError);
  EXPECT_THROW(make_algorithms({"robust", "robust=peg3d"}, {}), InputError);
  for (const char* bad : {"=robust", "a.b=robust", "a b=robust"}) {
    try {
      make_algorithms({bad}, {});
      ADD_FAILURE() << bad;
    } catch (const InvalidParameter& e) {
      EXPECT_EQ(e.parameter(), "--algorithms") << bad;
    }
  }
  EXPECT_THROW(make_algorithms({"mine=no-such-preset"}, {}), InputError);
}

}  // namespace
}  // namespace peg3d::experiment
