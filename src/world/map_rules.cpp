#include "world/map_rules.hpp"

#include <cmath>

#include <fmt/format.h>

namespace peg3d::world {
namespace {

std::string vec_text(const Vec3& v) { return fmt::format("({}, {}, {})", v.x(), v.y(), v.z()); }

Problem outside(const char* field, const Vec3& p, const Box& arena) {
  if (arena.contains(p)) return {};
  return {field, fmt::format("{} lies outside the arena [{} .. {}]", vec_text(p), vec_text(arena.lo), vec_text(arena.hi))};
}

Problem positive(const char* field, double v) {
  if (std::isfinite(v) && v > 0.0) return {};
  return {field, std::isfinite(v) ? fmt::format("must be > 0, got {}", v) : "must be a finite number"};
}

Problem finite(const char* field, const Vec3& v) {
  if (v.allFinite()) return {};
  return {field, "must be finite"};
}

}  // namespace

bool is_safe_name(std::string_view name) {
  if (name.empty() || name.size() > 64 || name.front() == '.') return false;
  for (const char c : name) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' ||
                    c == '_' || c == '.';
    if (!ok) return false;
  }
  return true;
}

Problem check_in_arena(const Vec3& p, const Box& arena) { return outside("", p, arena); }

Problem check_arena(const Vec3& min, const Vec3& size) {
  if (auto p = finite("min", min)) return p;
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(size[i]) || !(size[i] > 0.0)) {
      return {fmt::format("size[{}]", i), std::isfinite(size[i]) ? fmt::format("must be > 0, got {}", size[i]) : "must be finite"};
    }
  }
  return {};
}

Problem check_occupancy(const Box& arena, double resolution, double max_distance) {
  if (auto p = positive("resolution", resolution)) return p;
  const Vec3 size = arena.size();
  if (size.minCoeff() < resolution) {
    return {"resolution", fmt::format("{} m is coarser than the arena's smallest side ({} m)", resolution, size.minCoeff())};
  }
  // OctoMap keys are 16-bit: coordinates must stay within +-32767 voxels of the origin (with a margin).
  const double extent = std::max(arena.lo.cwiseAbs().maxCoeff(), arena.hi.cwiseAbs().maxCoeff());
  if (extent / resolution > 32000.0) {
    return {"resolution", fmt::format("{} m is too fine for an arena reaching {} m from the origin (OctoMap allows "
                                      "32000 voxels)",
                                      resolution, extent)};
  }
  if (!std::isfinite(max_distance) || max_distance < resolution) {
    return {"max_distance", fmt::format("must be >= occupancy.resolution ({} m), got {}", resolution, max_distance)};
  }
  return {};
}

Problem check_sphere(const SphereObstacle& s, const Box& arena) {
  if (auto p = finite("center", s.center)) return p;
  if (auto p = outside("center", s.center, arena)) return p;
  return positive("radius", s.radius);
}

Problem check_cylinder(const CylinderObstacle& c, const Box& arena) {
  if (auto p = finite("base", c.base)) return p;
  if (auto p = outside("base", c.base, arena)) return p;
  if (auto p = positive("radius", c.radius)) return p;
  return positive("height", c.height);
}

Problem check_placement(const TerrainMesh& t) {
  if (auto p = positive("scale", t.scale)) return p;
  if (auto p = finite("rotation_deg", t.rotation_deg)) return p;
  return finite("translation", t.translation);
}

Problem check_start(const Vec3& p, const Box& arena) {
  if (p.allFinite() && (p.array() > arena.lo.array()).all() && (p.array() < arena.hi.array()).all()) return {};
  return {"", fmt::format("start {} lies outside the arena [{} .. {}]", vec_text(p), vec_text(arena.lo), vec_text(arena.hi))};
}

Problem check_scenario_name(std::string_view name) {
  if (is_safe_name(name)) return {};
  return {"", fmt::format("'{}' cannot name a scenario: use 1 to 64 letters, digits, '-', '_' and '.', not starting with "
                          "'.' (scenario names name result files)",
                          name)};
}

void validate_map(const MapSpec& spec) {
  const auto fail = [&](const std::string& where, const Problem& p, int line = 0) {
    const std::string field = p.field.empty() ? where : (where.empty() ? p.field : where + "." + p.field);
    throw MapError(spec.source, line, field, p.message);
  };
  if (auto p = check_arena(spec.bounds.lo, spec.bounds.size())) fail("arena", p);
  if (auto p = check_occupancy(spec.bounds, spec.resolution, spec.max_distance)) fail("occupancy", p);
  for (std::size_t i = 0; i < spec.spheres.size(); ++i)
    if (auto p = check_sphere(spec.spheres[i], spec.bounds)) fail(fmt::format("spheres[{}]", i), p);
  for (std::size_t i = 0; i < spec.cylinders.size(); ++i)
    if (auto p = check_cylinder(spec.cylinders[i], spec.bounds)) fail(fmt::format("cylinders[{}]", i), p);
  for (std::size_t i = 0; i < spec.meshes.size(); ++i)
    if (auto p = check_placement(spec.meshes[i])) fail(fmt::format("terrain[{}]", i), p, spec.meshes[i].line);
  for (std::size_t k = 0; k < spec.scenarios.size(); ++k) {
    const Scenario& s = spec.scenarios[k];
    const std::string where = fmt::format("scenarios[{}]", k);
    if (auto p = check_scenario_name(s.name)) fail(where + ".name", p, s.line);
    for (std::size_t j = 0; j < k; ++j)
      if (spec.scenarios[j].name == s.name) fail(where + ".name", {"", fmt::format("duplicate scenario name '{}'", s.name)}, s.line);
    if (s.pursuers.empty()) fail(where + ".pursuers", {"", "needs at least one pursuer"}, s.line);
    if (s.evaders.empty()) fail(where + ".evaders", {"", "needs at least one evader"}, s.line);
    for (const auto* list : {&s.pursuers, &s.evaders}) {
      for (std::size_t i = 0; i < list->size(); ++i) {
        const AgentStart& a = (*list)[i];
        const std::string field =
            a.field.empty() ? fmt::format("{}.{}[{}].position", where, list == &s.pursuers ? "pursuers" : "evaders", i) : a.field;
        if (auto p = check_start(a.position, spec.bounds)) fail(field, p, a.line);
      }
    }
  }
}

}  // namespace peg3d::world
