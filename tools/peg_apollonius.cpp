// peg-apollonius: the generalized Apollonius surface and the optimal motion cones for a pursuer/evader pair
// (paper section 3.1). Prints a table, or JSON with --json (used by the plotting scripts).
#include <cstdio>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "core/validation.hpp"
#include "geometry/angles.hpp"
#include "geometry/apollonius.hpp"
#include "geometry/motion_cone.hpp"
#include "results/result_files.hpp"

int main(int argc, char** argv) {
  using namespace peg3d;
  CLI::App app{"Generalized Apollonius surface and optimal motion cones (paper section 3.1)"};
  std::vector<double> pursuer{10, 10, 10}, evader{-10, -10, 10};
  double vp = 1.1, ve = 1.0;
  std::vector<double> ratios;
  bool json = false;
  app.add_option("--pursuer", pursuer, "pursuer position x y z (m)")->expected(3)->capture_default_str();
  app.add_option("--evader", evader, "evader position x y z (m)")->expected(3)->capture_default_str();
  app.add_option("--vp", vp, "pursuer speed (m/s)")->capture_default_str();
  app.add_option("--ve", ve, "evader speed (m/s)")->capture_default_str();
  app.add_option("--ratios", ratios, "extra speed ratios a = vE/vP to show (e.g. 0.5 1 2)");
  app.add_flag("--json", json, "print JSON instead of a table");
  return cli::guarded_main(app, argc, argv, [&] {
    const Vec3 p(pursuer[0], pursuer[1], pursuer[2]), e(evader[0], evader[1], evader[2]);
    require_positive("vp", vp);
    require_positive("ve", ve);
    if ((p - e).norm() == 0.0) throw InvalidParameter("evader", "the pursuer's position", "must differ from the pursuer");
    ratios.insert(ratios.begin(), ve / vp);

    const nlohmann::json out = results::apollonius_to_json(p, e, vp, ve, ratios);
    const double pursuer_half_angle = out["pursuer_cone"]["half_angle_rad"].get<double>();
    const double evader_half_angle = out["evader_cone"]["half_angle_rad"].get<double>();
    if (json) {
      std::puts(out.dump(2).c_str());
      return 0;
    }
    fmt::print("P = ({}, {}, {}) m, vP = {} m/s;  E = ({}, {}, {}) m, vE = {} m/s;  |PE| = {:.4f} m\n", p.x(), p.y(),
               p.z(), vp, e.x(), e.y(), e.z(), ve, (p - e).norm());
    fmt::print("{:>8}  {:<7}  {:<36}  {}\n", "a", "surface", "center / point (m)", "radius (m) / normal");
    for (const auto& item : out["surfaces"]) {
      const bool sphere = item["kind"] == "sphere";
      const auto& c = sphere ? item["center"] : item["point"];
      fmt::print("{:>8.5f}  {:<7}  ({:10.4f}, {:10.4f}, {:10.4f})  {}\n", item["a"].get<double>(),
                 item["kind"].get<std::string>(), c[0].get<double>(), c[1].get<double>(), c[2].get<double>(),
                 sphere ? fmt::format("{:.4f} (encloses the {})", item["radius"].get<double>(),
                                      item["encloses"].get<std::string>())
                        : item["normal"].dump());
    }
    fmt::print("pursuer cone: half-angle alpha2* = asin(vE/vP) = {:.6f} rad ({:.3f} deg) about P->E\n", pursuer_half_angle,
               pursuer_half_angle * 180 / kPi);
    fmt::print("evader space: alpha1 >= pi/2, a half-space about P->E (half-angle {:.6f} rad)\n", evader_half_angle);
    if (out.contains("interception_fleeing")) {
      const auto& x = out["interception_fleeing"];
      fmt::print("evader fleeing along P->E is intercepted at ({:.4f}, {:.4f}, {:.4f})\n", x[0].get<double>(),
                 x[1].get<double>(), x[2].get<double>());
    }
    return 0;
  });
}
