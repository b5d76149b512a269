#include "experiment/experiment.hpp"

#include <fmt/format.h>

#include "sweep/sweep_driver.hpp"

namespace peg3d::experiment {

void run_experiment(Experiment& e, int threads, const sweep::SweepControl& control, bool root) {
  e.begin(control);
  sweep::run_sweep(e.run_count(), threads, control,
                   {.run = [&e](std::size_t i) { e.run_one(i); },
                    .encode = [&e](std::size_t i) { return e.encode(i); },
                    .restore = [&e](std::size_t i, const nlohmann::json& record) { e.restore(i, record); }});
  e.finish(root);
}

std::string ending_of(const game::EpisodeResult& result) {
  return fmt::format("{} at {:.1f} s", game::to_string(result.outcome), result.duration);
}

}  // namespace peg3d::experiment
