#include "world/map/map_rules.hpp"

#include <cmath>
#include <cstdint>
#include <optional>
#include <unordered_map>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "world/map/movers.hpp"
#include "world/map/obstacle_geometry.hpp"

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
                          shown(name))};
}

Problem check_physics(const PhysicsSpec& physics) {
  if (physics.rate_hz < 1 || physics.rate_hz > 100000) {
    return {"rate_hz", fmt::format("must lie in [1, 100000], got {}", physics.rate_hz)};
  }
  if (const std::optional<int> k = physics.keyframe_hz; k && (*k < 0 || *k > physics.rate_hz || (*k > 0 && physics.rate_hz % *k != 0))) {
    return {"keyframe_hz", fmt::format("must be 0 (every substep) or divide rate_hz = {} into whole substeps, got {}",
                                       physics.rate_hz, *k)};
  }
  return finite("gravity", physics.gravity);
}

Pose start_pose(const MoverSpec& m) {
  if (m.kinematic()) return scripted_pose(m, 0.0);
  return {m.start, orientation_deg(m.rotation_deg)};
}

Problem check_mover(const MoverSpec& m, const Box& arena) {
  switch (m.shape.kind) {
    case Shape::Kind::kSphere:
      if (auto p = positive("radius", m.shape.radius)) return p;
      break;
    case Shape::Kind::kCylinder:
      if (auto p = positive("radius", m.shape.radius)) return p;
      if (auto p = positive("height", m.shape.height)) return p;
      break;
    case Shape::Kind::kBox:
      for (int i = 0; i < 3; ++i) {
        if (auto p = positive("size", m.shape.size[i])) return {fmt::format("size[{}]", i), p.message};
      }
      break;
  }
  if (auto p = finite("rotation_deg", m.rotation_deg)) return p;
  const double reach = m.shape.bounding_radius();
  const Box inside = arena.shrunk(reach);
  const auto keeps_inside = [&](const char* field, const Vec3& c) -> Problem {
    if (inside.contains(c)) return {};
    return {field, fmt::format("{} is closer than the mover's reach ({} m) to the arena's faces [{} .. {}]", vec_text(c),
                               reach, vec_text(arena.lo), vec_text(arena.hi))};
  };
  switch (m.motion) {
    case MoverSpec::Motion::kPath: {
      const auto& w = m.path.waypoints;
      if (w.size() < 2) return {"path.waypoints", fmt::format("needs at least 2 waypoints, got {}", w.size())};
      for (std::size_t i = 0; i < w.size(); ++i) {
        const std::string field = fmt::format("path.waypoints[{}]", i);
        if (!w[i].allFinite()) return {field, "must be finite"};
        // The arena box shrunk by the reach is convex: straight segments between inside waypoints stay inside.
        if (auto p = keeps_inside("", w[i])) return {field, p.message};
        if (i > 0 && (w[i] - w[i - 1]).norm() == 0.0) return {field, "repeats the waypoint before it"};
      }
      return positive("path.speed", m.path.speed);
    }
    case MoverSpec::Motion::kOrbit: {
      const OrbitMotion& o = m.orbit;
      if (auto p = finite("orbit.center", o.center)) return p;
      if (auto p = positive("orbit.radius", o.radius)) return p;
      if (auto p = positive("orbit.period", o.period)) return p;
      if (!o.axis.allFinite() || o.axis.norm() == 0.0) return {"orbit.axis", "must be a non-zero, finite direction"};
      if (!std::isfinite(o.phase)) return {"orbit.phase_deg", "must be finite"};
      // The circle's extent along world axis i is radius * sqrt(1 - a_i^2) about the centre.
      const Vec3 a = o.axis.normalized();
      for (int i = 0; i < 3; ++i) {
        const double e = o.radius * std::sqrt(std::max(0.0, 1.0 - a[i] * a[i]));
        if (o.center[i] - e < inside.lo[i] - 1e-12 || o.center[i] + e > inside.hi[i] + 1e-12) {
          return {"orbit", fmt::format("the orbit leaves the arena: it spans [{}, {}] m on {} and the mover reaches {} m "
                                       "beyond its centre",
                                       o.center[i] - e, o.center[i] + e, "xyz"[i], reach)};
        }
      }
      return {};
    }
    case MoverSpec::Motion::kDynamic: {
      const DynamicMotion& d = m.dynamic;
      if (!m.start.allFinite()) return {"dynamic.position", "must be finite"};
      if (auto p = keeps_inside("dynamic.position", m.start)) return p;
      if (auto p = positive("dynamic.mass", d.mass)) return p;
      if (auto p = finite("dynamic.velocity", d.velocity)) return p;
      if (auto p = finite("dynamic.angular_velocity", d.angular_velocity)) return p;
      if (!std::isfinite(d.friction) || d.friction < 0.0) return {"dynamic.friction", fmt::format("must be >= 0, got {}", d.friction)};
      if (!std::isfinite(d.rolling_friction) || d.rolling_friction < 0.0) {
        return {"dynamic.rolling_friction", fmt::format("must be >= 0, got {}", d.rolling_friction)};
      }
      if (!std::isfinite(d.restitution) || d.restitution < 0.0 || d.restitution > 1.0) {
        return {"dynamic.restitution", fmt::format("must lie in [0, 1], got {}", d.restitution)};
      }
      return {};
    }
  }
  return {};
}

Problem check_mover_start(const MoverSpec& m, const MapSpec& spec, const std::vector<TriangleMesh>& meshes) {
  const Pose pose = start_pose(m);
  for (std::size_t i = 0; i < spec.spheres.size(); ++i) {
    const SphereObstacle& s = spec.spheres[i];
    if (nearest_on_shape(m.shape, pose, s.center).distance < s.radius) {
      return {"", fmt::format("starts overlapping sphere obstacle {} at {}", i, vec_text(s.center))};
    }
  }
  for (std::size_t i = 0; i < spec.cylinders.size(); ++i) {
    const CylinderObstacle& c = spec.cylinders[i];
    // The cylinder against the mover's bounding ball: conservative for boxes and cylinders.
    const Shape cyl{Shape::Kind::kCylinder, c.radius, c.height, Vec3::Ones()};
    const Pose at{c.base + Vec3(0, 0, 0.5 * c.height), Quat::Identity()};
    const double reach = m.shape.kind == Shape::Kind::kSphere ? m.shape.radius : m.shape.bounding_radius();
    if (nearest_on_shape(cyl, at, pose.position).distance < reach) {
      return {"", fmt::format("starts overlapping cylinder obstacle {} at {}", i, vec_text(c.base))};
    }
  }
  for (std::size_t i = 0; i < spec.meshes.size() && i < meshes.size(); ++i) {
    if (spec.meshes[i].solid_below && is_below_surface(meshes[i], pose.position)) {
      return {"", fmt::format("starts under the solid terrain {}", i)};
    }
  }
  return {};
}

Problem check_mover_clear_of_start(const MoverSpec& m, const Vec3& start) {
  if (nearest_on_shape(m.shape, start_pose(m), start).distance > 0.0) return {};
  return {"", fmt::format("holds the agent start {} at t = 0", vec_text(start))};
}

namespace {

// Whether two dynamic bodies start inside each other: balls that overlap, or either's centre inside the other
// (copies of one body, which Bullet would fling apart with every pair in contact at once).
bool start_inside(const MoverSpec& a, const MoverSpec& b) {
  const Pose pa = start_pose(a), pb = start_pose(b);
  if (a.shape.kind == Shape::Kind::kSphere && b.shape.kind == Shape::Kind::kSphere) {
    return (pa.position - pb.position).norm() < a.shape.radius + b.shape.radius;
  }
  return signed_distance(a.shape, pa, pb.position) < 0.0 || signed_distance(b.shape, pb, pa.position) < 0.0;
}

// The first pair (lower index second) of dynamic bodies that start inside each other, by a grid of cells two
// of the largest bounding radii wide: only bodies in neighbouring cells can.
std::optional<std::pair<std::size_t, std::size_t>> dynamic_overlap(const MapSpec& spec) {
  double reach = 0.0;
  for (const MoverSpec& m : spec.movers) {
    if (!m.kinematic()) reach = std::max(reach, m.shape.bounding_radius());
  }
  if (!(reach > 0.0)) return std::nullopt;
  const double cell = 2.0 * reach;
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> grid;
  const auto key = [](long x, long y, long z) {
    return (std::uint64_t(x & 0x1fffff) << 42) | (std::uint64_t(y & 0x1fffff) << 21) | std::uint64_t(z & 0x1fffff);
  };
  for (std::size_t i = 0; i < spec.movers.size(); ++i) {
    const MoverSpec& m = spec.movers[i];
    if (m.kinematic()) continue;
    const long cx = std::lround(std::floor(m.start.x() / cell)), cy = std::lround(std::floor(m.start.y() / cell)),
               cz = std::lround(std::floor(m.start.z() / cell));
    for (long dx = -1; dx <= 1; ++dx)
      for (long dy = -1; dy <= 1; ++dy)
        for (long dz = -1; dz <= 1; ++dz) {
          const auto it = grid.find(key(cx + dx, cy + dy, cz + dz));
          if (it == grid.end()) continue;
          for (const std::size_t j : it->second) {
            if (start_inside(spec.movers[j], m)) return std::pair{i, j};
          }
        }
    grid[key(cx, cy, cz)].push_back(i);
  }
  return std::nullopt;
}

}  // namespace

void validate_movers(const MapSpec& spec, const std::vector<TriangleMesh>& meshes) {
  if (const auto pair = dynamic_overlap(spec)) {
    throw MapError(spec.source, spec.movers[pair->first].line, fmt::format("movers[{}]", pair->first),
                   fmt::format("starts inside dynamic body movers[{}]: dynamic bodies must start apart", pair->second));
  }
  for (std::size_t i = 0; i < spec.movers.size(); ++i) {
    const MoverSpec& m = spec.movers[i];
    const std::string field = fmt::format("movers[{}]", i);
    if (const Problem p = check_mover_start(m, spec, meshes)) throw MapError(spec.source, m.line, field, p.message);
    for (const Scenario& s : spec.scenarios) {
      for (const auto* list : {&s.pursuers, &s.evaders}) {
        for (const AgentStart& a : *list) {
          if (const Problem p = check_mover_clear_of_start(m, a.position)) {
            throw MapError(spec.source, m.line, field,
                           p.message + (a.field.empty() ? std::string() : " (" + a.field + ")"));
          }
        }
      }
    }
  }
}

void validate_map(const MapSpec& spec) {
  const auto fail = [&](const std::string& where, const Problem& p, int line = 0) {
    const std::string field = p.field.empty() ? where : (where.empty() ? p.field : where + "." + p.field);
    throw MapError(spec.source, line, field, p.message);
  };
  if (auto p = check_arena(spec.bounds.lo, spec.bounds.size())) fail("arena", p);
  if (auto p = check_occupancy(spec.bounds, spec.resolution, spec.max_distance)) fail("occupancy", p);
  if (spec.spheres.size() + spec.cylinders.size() > std::size_t(kMaxObstacles)) {
    fail("obstacles", {"", fmt::format("{} obstacles, more than the {} a map may hold",
                                       spec.spheres.size() + spec.cylinders.size(), kMaxObstacles)});
  }
  if (spec.movers.size() > std::size_t(kMaxMovers)) {
    fail("movers", {"", fmt::format("{} movers, more than the {} a map may hold", spec.movers.size(), kMaxMovers)});
  }
  for (std::size_t i = 0; i < spec.spheres.size(); ++i)
    if (auto p = check_sphere(spec.spheres[i], spec.bounds)) fail(fmt::format("spheres[{}]", i), p);
  for (std::size_t i = 0; i < spec.cylinders.size(); ++i)
    if (auto p = check_cylinder(spec.cylinders[i], spec.bounds)) fail(fmt::format("cylinders[{}]", i), p);
  for (std::size_t i = 0; i < spec.meshes.size(); ++i)
    if (auto p = check_placement(spec.meshes[i])) fail(fmt::format("terrain[{}]", i), p, spec.meshes[i].line);
  if (auto p = check_physics(spec.physics)) fail("physics", p, spec.physics.line);
  for (std::size_t i = 0; i < spec.movers.size(); ++i)
    if (auto p = check_mover(spec.movers[i], spec.bounds)) fail(fmt::format("movers[{}]", i), p, spec.movers[i].line);
  for (std::size_t k = 0; k < spec.scenarios.size(); ++k) {
    const Scenario& s = spec.scenarios[k];
    const std::string where = fmt::format("scenarios[{}]", k);
    if (auto p = check_scenario_name(s.name)) fail(where + ".name", p, s.line);
    for (std::size_t j = 0; j < k; ++j)
      if (spec.scenarios[j].name == s.name) fail(where + ".name", {"", fmt::format("duplicate scenario name '{}'", shown(s.name))}, s.line);
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
