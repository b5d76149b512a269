#pragma once
// The rules a map must follow, each stated once. load_map() applies them while reading a file (and reports
// the offending value's line); Arena::build() applies them to maps written in code. A rule returns the
// first Problem it finds: the field (relative to the thing checked, e.g. "radius") and what is wrong.

#include <string>
#include <string_view>

#include "geometry/vector.hpp"
#include "world/map/map_spec.hpp"
#include "world/map/triangle_mesh.hpp"

namespace peg3d::world {

struct Problem {
  std::string field;    ///< relative field, e.g. "radius", "size[2]"; empty for the thing as a whole
  std::string message;  ///< empty when there is no problem
  explicit operator bool() const { return !message.empty(); }
};

/// A point inside the (closed) arena box: what obstacles' centres and generator regions must satisfy.
Problem check_in_arena(const Vec3& p, const Box& arena);
/// The arena box: finite, every side of `size` > 0 (fields "min", "size[i]").
Problem check_arena(const Vec3& min, const Vec3& size);
/// Occupancy settings for the arena: resolution > 0, not coarser than the smallest side, within OctoMap's
/// 16-bit keys; max_distance >= resolution (fields "resolution", "max_distance").
Problem check_occupancy(const Box& arena, double resolution, double max_distance);
/// A sphere: finite centre inside the arena, radius > 0 ("center", "radius").
Problem check_sphere(const SphereObstacle& s, const Box& arena);
/// A cylinder: finite base inside the arena, radius and height > 0 ("base", "radius", "height").
Problem check_cylinder(const CylinderObstacle& c, const Box& arena);
/// A terrain placement: scale > 0, finite rotation and translation ("scale", "rotation_deg", "translation").
Problem check_placement(const TerrainMesh& t);
/// A start point: finite and strictly inside the arena.
Problem check_start(const Vec3& p, const Box& arena);
/// A scenario name (it names result files): see is_safe_name().
Problem check_scenario_name(std::string_view name);
/// The physics settings: a rate in [1, 100000] Hz, finite gravity ("rate_hz", "gravity").
Problem check_physics(const PhysicsSpec& physics);
/// A mover's shape and motion: positive sizes ("radius", "height", "size"), a path of at least two distinct
/// consecutive waypoints and a positive speed ("path.waypoints[i]", "path.speed"), an orbit with positive radius
/// and period and a non-zero axis ("orbit.radius", ...), a dynamic body with positive mass, non-negative
/// friction and restitution in [0, 1] ("dynamic.mass", ...); and its whole motion inside the arena: every point
/// of a path or orbit, and a dynamic body's start, at least the shape's bounding radius from every face.
Problem check_mover(const MoverSpec& mover, const Box& arena);
/// A mover's start (t = 0) against the static obstacles and the terrain: it must not overlap a sphere or
/// cylinder, nor start under solid terrain (field "start"). `meshes` are the placed terrain meshes, in
/// spec.meshes' order.
Problem check_mover_start(const MoverSpec& mover, const MapSpec& spec, const std::vector<TriangleMesh>& meshes);
/// A mover's shape at t = 0 must not hold an agent's start point.
Problem check_mover_clear_of_start(const MoverSpec& mover, const Vec3& start);
/// The pose of a mover at t = 0.
Pose start_pose(const MoverSpec& mover);

/// check_mover_start and check_mover_clear_of_start for every mover and every agent start of the spec: throws
/// MapError naming spec.source, the mover's line and "movers[i]".
void validate_movers(const MapSpec& spec, const std::vector<TriangleMesh>& meshes);

/// Every rule over a whole spec (a map built in code): throws MapError naming spec.source, the line when the
/// spec carries one, and the field (e.g. "spheres[3].radius").
void validate_map(const MapSpec& spec);

}  // namespace peg3d::world
