// load_map(): the YAML map format of docs/maps.md. Every check names the file, the line and the field.

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string_view>
#include <system_error>
#include <tuple>
#include <utility>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "core/input_files.hpp"
#include "core/yaml_input.hpp"
#include "world/map/map_rules.hpp"
#include "world/map/map_loader.hpp"
#include "world/map/map_spec.hpp"
#include "world/map/movers.hpp"
#include "world/map/random_obstacles.hpp"
#include "world/map/triangle_mesh.hpp"
#include "world/map/yaml_reader.hpp"

namespace peg3d::world {

namespace {

using YAML::Node;

constexpr int kFormatVersion = 1;

std::string format_vec(const Vec3& v) { return fmt::format("({}, {}, {})", v.x(), v.y(), v.z()); }

/// Where a start came from, for messages about it.
struct StartRef {
  Vec3 position;
  std::string field;
  int line;
};

class Loader : public YamlReader {
 public:
  explicit Loader(std::filesystem::path file) : YamlReader(std::move(file), &throw_error<MapError>) {}

  MapSpec load();

 private:
  void read_arena(const Node& n, MapSpec& spec);
  void read_occupancy(const Node* n, MapSpec& spec);
  AgentStart read_agent(const Node& n, const std::string& field);
  Scenario read_scenario(const Node& n, const std::string& field, std::string name);
  void read_obstacle(const Node& n, const std::string& field, MapSpec& spec);
  void read_terrain(const Node& n, const std::string& field, MapSpec& spec);
  void read_generator(const Node& n, const std::string& field, MapSpec& spec);
  void read_physics(const Node& n, MapSpec& spec);
  void read_mover(const Node& n, const std::string& field, MapSpec& spec);
  void check_starts(const MapSpec& spec) const;
  void require_in_arena(const Node& n, const std::string& field, const Vec3& p, const MapSpec& spec) const;

  std::vector<StartRef> starts_;
};

void Loader::require_in_arena(const Node& n, const std::string& field, const Vec3& p, const MapSpec& spec) const {
  if (const Problem problem = check_in_arena(p, spec.bounds)) fail(n, field, problem.message);
}

void Loader::read_arena(const Node& n, MapSpec& spec) {
  const Fields f(*this, n, "arena");
  f.allow({"min", "size", "faces_are_obstacles"});
  const Vec3 lo = f.find("min") ? vec3(*f.find("min"), f.field("min")) : Vec3::Zero();
  const Node& size_node = f.need("size");
  const Vec3 size = vec3(size_node, f.field("size"));
  if (const Problem p = check_arena(lo, size)) {
    // p.field is "min" or "size[i]": report the offending number's own line.
    const Node& at = p.field == "min" ? *f.find("min") : size_node[std::size_t(p.field.at(5) - '0')];
    fail(at, f.field(p.field), p.message);
  }
  spec.bounds = Box{lo, lo + size};
  if (const Node* faces = f.find("faces_are_obstacles")) {
    const Fields ff(*this, *faces, f.field("faces_are_obstacles"));
    ff.allow({"floor", "ceiling", "walls"});
    if (const Node* v = ff.find("floor")) spec.floor_is_obstacle = boolean(*v, ff.field("floor"));
    if (const Node* v = ff.find("ceiling")) spec.ceiling_is_obstacle = boolean(*v, ff.field("ceiling"));
    if (const Node* v = ff.find("walls")) spec.walls_is_obstacle = boolean(*v, ff.field("walls"));
  }
}

void Loader::read_occupancy(const Node* n, MapSpec& spec) {
  int line = 1, max_line = 1;
  if (n != nullptr) {
    const Fields f(*this, *n, "occupancy");
    f.allow({"resolution", "max_distance"});
    line = max_line = line_of(*n);
    if (const Node* v = f.find("resolution")) spec.resolution = number(*v, f.field("resolution")), line = line_of(*v);
    if (const Node* v = f.find("max_distance")) {
      spec.max_distance = number(*v, f.field("max_distance"));
      max_line = line_of(*v);
    }
  }
  if (const Problem p = check_occupancy(spec.bounds, spec.resolution, spec.max_distance)) {
    fail(p.field == "max_distance" ? max_line : line, "occupancy." + p.field, p.message);
  }
}

AgentStart Loader::read_agent(const Node& n, const std::string& field) {
  const Fields f(*this, n, field);
  f.allow({"position", "heading"});
  AgentStart a;
  const Node& pos = f.need("position");
  a.position = vec3(pos, f.field("position"));
  a.field = f.field("position");
  a.line = line_of(pos);
  starts_.push_back({a.position, a.field, a.line});
  if (const Node* h = f.find("heading")) {
    const Fields hf(*this, *h, f.field("heading"));
    hf.allow({"alpha_deg", "theta_deg"});
    const double alpha = number(hf.need("alpha_deg"), hf.field("alpha_deg"));
    const Node& theta_node = hf.need("theta_deg");
    const double theta = number(theta_node, hf.field("theta_deg"));
    if (theta < 0.0 || theta > 180.0) fail(theta_node, hf.field("theta_deg"), fmt::format("must lie in [0, 180], got {}", theta));
    a.heading = Heading{wrap_angle(alpha * kPi / 180.0), theta * kPi / 180.0};
  }
  return a;
}

Scenario Loader::read_scenario(const Node& n, const std::string& field, std::string name) {
  const Fields f(*this, n, field);
  if (name.empty()) {
    f.allow({"name", "pursuer", "pursuers", "evader", "evaders"});
    const Node& name_node = f.need("name");
    name = text(name_node, f.field("name"));
    if (const Problem p = check_scenario_name(name)) fail(name_node, f.field("name"), p.message);
  } else {
    f.allow({"pursuer", "pursuers", "evader", "evaders"});
  }
  Scenario s;
  s.name = std::move(name);
  s.line = line_of(n);
  // Each role: one agent (`pursuer: {...}`) or a list of them (`pursuers: [{...}, ...]`).
  for (const auto& [one, many, out] : {std::tuple{"pursuer", "pursuers", &s.pursuers}, std::tuple{"evader", "evaders", &s.evaders}}) {
    const Node* single = f.find(one);
    const Node* list = f.find(many);
    if (single != nullptr && list != nullptr) fail(*list, f.field(many), fmt::format("give either '{}' or '{}', not both", one, many));
    if (single != nullptr) {
      out->push_back(read_agent(*single, f.field(one)));
    } else if (list != nullptr) {
      sequence(*list, f.field(many));
      if (list->size() < 1 || list->size() > static_cast<std::size_t>(kMaxAgentsPerRole)) {
        fail(*list, f.field(many), fmt::format("needs 1 to {} entries, got {}", kMaxAgentsPerRole, list->size()));
      }
      for (std::size_t i = 0; i < list->size(); ++i) out->push_back(read_agent((*list)[i], fmt::format("{}[{}]", f.field(many), i)));
    } else {
      fail(n, f.field(one), fmt::format("missing required field (or give '{}', a list)", many));
    }
  }
  return s;
}

void Loader::read_obstacle(const Node& n, const std::string& field, MapSpec& spec) {
  const Fields f(*this, n, field);
  const Node& kind_node = f.need("kind");
  const std::string kind = text(kind_node, f.field("kind"));
  if (kind == "sphere") {
    f.allow({"kind", "center", "radius"});
    const SphereObstacle s{vec3(f.need("center"), f.field("center")), number(f.need("radius"), f.field("radius"))};
    if (const Problem p = check_sphere(s, spec.bounds)) fail(f.need(p.field), f.field(p.field), p.message);
    spec.spheres.push_back(s);
  } else if (kind == "cylinder") {
    f.allow({"kind", "base", "radius", "height"});
    const CylinderObstacle c{vec3(f.need("base"), f.field("base")), number(f.need("radius"), f.field("radius")),
                             number(f.need("height"), f.field("height"))};
    if (const Problem p = check_cylinder(c, spec.bounds)) fail(f.need(p.field), f.field(p.field), p.message);
    spec.cylinders.push_back(c);
  } else {
    fail(kind_node, f.field("kind"), fmt::format("unknown obstacle kind '{}' (allowed: sphere, cylinder)", shown(kind)));
  }
}

void Loader::read_terrain(const Node& n, const std::string& field, MapSpec& spec) {
  const Fields f(*this, n, field);
  f.allow({"file", "scale", "rotation_deg", "translation", "solid_below"});
  TerrainMesh t;
  t.line = line_of(n);
  const Node& file_node = f.need("file");
  const std::filesystem::path rel = text(file_node, f.field("file"));
  t.file = std::filesystem::absolute((file().parent_path() / rel).lexically_normal());
  if (const Node* v = f.find("scale")) t.scale = number(*v, f.field("scale"));
  if (const Node* v = f.find("rotation_deg")) t.rotation_deg = vec3(*v, f.field("rotation_deg"));
  if (const Node* v = f.find("translation")) t.translation = vec3(*v, f.field("translation"));
  if (const Node* v = f.find("solid_below")) t.solid_below = boolean(*v, f.field("solid_below"));
  if (const Problem p = check_placement(t)) fail(f.need(p.field), f.field(p.field), p.message);
  // Imported once: the Arena builds from this copy instead of reading the file again.
  auto mesh = std::make_shared<TriangleMesh>();
  try {
    *mesh = load_terrain_mesh(t);
  } catch (const MeshError& e) {
    fail(file_node, f.field("file"), e.what());
  }
  const Box b = mesh->bounds();
  const bool apart = (b.hi.array() < spec.bounds.lo.array()).any() || (b.lo.array() > spec.bounds.hi.array()).any();
  if (apart) {
    fail(n, field, fmt::format("mesh '{}' lies entirely outside the arena (placed bounds {} .. {})", rel.string(),
                               format_vec(b.lo), format_vec(b.hi)));
  }
  t.imported = std::move(mesh);
  spec.meshes.push_back(t);
}

void Loader::read_physics(const Node& n, MapSpec& spec) {
  const Fields f(*this, n, "physics");
  f.allow({"gravity", "rate_hz", "keyframe_hz", "faces_are_physical"});
  spec.physics.line = line_of(n);
  if (const Node* v = f.find("gravity")) spec.physics.gravity = vec3(*v, f.field("gravity"));
  if (const Node* v = f.find("rate_hz")) {
    const long long r = integer(*v, f.field("rate_hz"));
    spec.physics.rate_hz = static_cast<int>(std::clamp<long long>(r, -1, 1000000));
  }
  if (const Node* v = f.find("keyframe_hz")) {
    const long long r = integer(*v, f.field("keyframe_hz"));
    spec.physics.keyframe_hz = static_cast<int>(std::clamp<long long>(r, -1, 1000000));
  }
  if (const Node* v = f.find("faces_are_physical")) spec.physics.faces_are_physical = boolean(*v, f.field("faces_are_physical"));
  if (const Problem p = check_physics(spec.physics)) fail(f.need(p.field), f.field(p.field), p.message);
}

void Loader::read_mover(const Node& n, const std::string& field, MapSpec& spec) {
  const Fields f(*this, n, field);
  MoverSpec m;
  m.line = line_of(n);
  const Node& kind_node = f.need("kind");
  const std::string kind = text(kind_node, f.field("kind"));
  std::vector<std::string_view> allowed{"kind", "rotation_deg", "path", "orbit", "dynamic"};
  if (kind == "sphere") {
    m.shape.kind = Shape::Kind::kSphere;
    allowed.push_back("radius");
    m.shape.radius = number(f.need("radius"), f.field("radius"));
  } else if (kind == "cylinder") {
    m.shape.kind = Shape::Kind::kCylinder;
    allowed.insert(allowed.end(), {"radius", "height"});
    m.shape.radius = number(f.need("radius"), f.field("radius"));
    m.shape.height = number(f.need("height"), f.field("height"));
  } else if (kind == "box") {
    m.shape.kind = Shape::Kind::kBox;
    allowed.push_back("size");
    m.shape.size = vec3(f.need("size"), f.field("size"));
  } else {
    fail(kind_node, f.field("kind"), fmt::format("unknown mover kind '{}' (allowed: sphere, cylinder, box)", shown(kind)));
  }
  f.allow(allowed);
  if (const Node* v = f.find("rotation_deg")) m.rotation_deg = vec3(*v, f.field("rotation_deg"));
  const Node* motions[] = {f.find("path"), f.find("orbit"), f.find("dynamic")};
  if ((motions[0] != nullptr) + (motions[1] != nullptr) + (motions[2] != nullptr) != 1) {
    fail(n, field, "needs exactly one motion: path, orbit or dynamic");
  }
  if (const Node* p = motions[0]) {
    m.motion = MoverSpec::Motion::kPath;
    const Fields pf(*this, *p, f.field("path"));
    pf.allow({"waypoints", "speed", "mode"});
    const Node& list = sequence(pf.need("waypoints"), pf.field("waypoints"));
    for (std::size_t i = 0; i < list.size(); ++i) {
      m.path.waypoints.push_back(vec3(list[i], fmt::format("{}[{}]", pf.field("waypoints"), i)));
    }
    m.path.speed = number(pf.need("speed"), pf.field("speed"));
    if (const Node* v = pf.find("mode")) {
      const std::string mode = text(*v, pf.field("mode"));
      if (mode != "loop" && mode != "back-and-forth") fail(*v, pf.field("mode"), fmt::format("'{}' is not loop or back-and-forth", shown(mode)));
      m.path.loop = mode == "loop";
    }
  } else if (const Node* o = motions[1]) {
    m.motion = MoverSpec::Motion::kOrbit;
    const Fields of(*this, *o, f.field("orbit"));
    of.allow({"center", "radius", "period", "axis", "phase_deg"});
    m.orbit.center = vec3(of.need("center"), of.field("center"));
    m.orbit.radius = number(of.need("radius"), of.field("radius"));
    m.orbit.period = number(of.need("period"), of.field("period"));
    if (const Node* v = of.find("axis")) m.orbit.axis = vec3(*v, of.field("axis"));
    if (const Node* v = of.find("phase_deg")) m.orbit.phase = number(*v, of.field("phase_deg")) * kPi / 180.0;
  } else {
    m.motion = MoverSpec::Motion::kDynamic;
    const Fields df(*this, *motions[2], f.field("dynamic"));
    df.allow({"position", "mass", "velocity", "angular_velocity", "friction", "rolling_friction", "restitution", "touch"});
    m.start = vec3(df.need("position"), df.field("position"));
    m.dynamic.mass = number(df.need("mass"), df.field("mass"));
    if (const Node* v = df.find("velocity")) m.dynamic.velocity = vec3(*v, df.field("velocity"));
    if (const Node* v = df.find("angular_velocity")) m.dynamic.angular_velocity = vec3(*v, df.field("angular_velocity"));
    if (const Node* v = df.find("friction")) m.dynamic.friction = number(*v, df.field("friction"));
    if (const Node* v = df.find("rolling_friction")) m.dynamic.rolling_friction = number(*v, df.field("rolling_friction"));
    if (const Node* v = df.find("restitution")) m.dynamic.restitution = number(*v, df.field("restitution"));
    if (const Node* v = df.find("touch")) {
      const std::string touch = text(*v, df.field("touch"));
      if (touch != "solid" && touch != "pushable") fail(*v, df.field("touch"), fmt::format("'{}' is not solid or pushable", shown(touch)));
      m.dynamic.touch = touch == "solid" ? DynamicMotion::Touch::kSolid : DynamicMotion::Touch::kPushable;
    }
  }
  if (const Problem p = check_mover(m, spec.bounds)) fail(node_of(f, p.field), field + "." + p.field, p.message);
  spec.movers.push_back(std::move(m));
}

void Loader::read_generator(const Node& n, const std::string& field, MapSpec& spec) {
  const Fields f(*this, n, field);
  const Node& kind_node = f.need("kind");
  const std::string kind = text(kind_node, f.field("kind"));
  RandomObstacleSpec g;
  if (kind == "sphere") {
    g.kind = RandomObstacleSpec::Kind::kSphere;
    f.allow({"kind", "count", "radius", "seed", "clearance_from_starts", "clearance_between", "region", "max_attempts"});
  } else if (kind == "cylinder") {
    g.kind = RandomObstacleSpec::Kind::kCylinder;
    f.allow({"kind", "count", "radius", "height", "seed", "clearance_from_starts", "clearance_between", "region",
             "max_attempts"});
    std::tie(g.height_min, g.height_max) = positive_range(f.need("height"), f.field("height"));
  } else {
    fail(kind_node, f.field("kind"), fmt::format("unknown obstacle kind '{}' (allowed: sphere, cylinder)", shown(kind)));
  }
  const Node& count_node = f.need("count");
  const long long count = integer(count_node, f.field("count"));
  const long long left = kMaxObstacles - static_cast<long long>(spec.spheres.size() + spec.cylinders.size());
  if (count < 0 || count > left) {
    fail(count_node, f.field("count"),
         fmt::format("must lie in [0, {}] (a map holds at most {} obstacles, {} before this generator), got {}",
                     std::max(left, 0LL), kMaxObstacles, spec.spheres.size() + spec.cylinders.size(), count));
  }
  g.count = static_cast<int>(count);
  const Node& radius_node = f.need("radius");
  std::tie(g.radius_min, g.radius_max) = positive_range(radius_node, f.field("radius"));
  g.seed = unsigned_integer(f.need("seed"), f.field("seed"));
  if (const Node* v = f.find("clearance_from_starts")) g.clearance_from_starts = non_negative(*v, f.field("clearance_from_starts"));
  if (const Node* v = f.find("clearance_between")) g.clearance_between = non_negative(*v, f.field("clearance_between"));
  if (const Node* v = f.find("max_attempts")) {
    const long long a = integer(*v, f.field("max_attempts"));
    if (a < 1 || a > 100000000) fail(*v, f.field("max_attempts"), fmt::format("must lie in [1, 100000000], got {}", a));
    g.max_attempts = static_cast<int>(a);
  }
  g.region = spec.bounds;
  if (const Node* r = f.find("region")) {
    const Fields rf(*this, *r, f.field("region"));
    rf.allow({"min", "max"});
    const Node& lo = rf.need("min");
    const Node& hi = rf.need("max");
    g.region = Box{vec3(lo, rf.field("min")), vec3(hi, rf.field("max"))};
    require_in_arena(lo, rf.field("min"), g.region.lo, spec);
    require_in_arena(hi, rf.field("max"), g.region.hi, spec);
    if (!(g.region.lo.array() < g.region.hi.array()).all()) fail(*r, rf.path(), "min must be below max on every axis");
  }
  const Vec3 room = g.region.size();
  const bool fits = g.kind == RandomObstacleSpec::Kind::kSphere ? room.minCoeff() >= 2.0 * g.radius_max
                                                                : room.head<2>().minCoeff() >= 2.0 * g.radius_max;
  if (!fits) {
    fail(radius_node, f.field("radius"),
         fmt::format("an obstacle of radius {} m does not fit in the placement region {} .. {}", g.radius_max,
                     format_vec(g.region.lo), format_vec(g.region.hi)));
  }
  std::vector<Vec3> starts;
  for (const StartRef& s : starts_) starts.push_back(s.position);
  // Random obstacles keep their clearance from the movers' whole routes too, as from balls of the movers' reach
  // along them, so no scripted mover ever runs through one and no dynamic body starts inside one.
  std::vector<SphereObstacle> keep_clear = spec.spheres;
  for (const MoverSpec& m : spec.movers) {
    for (const Vec3& c : route_samples(m, 0.5)) keep_clear.push_back({c, m.shape.bounding_radius()});
  }
  RandomObstacles placed = place_random_obstacles(g, starts, keep_clear, spec.cylinders);
  if (placed.placed() < g.count) {
    fail(count_node, f.field("count"),
         fmt::format("placed only {} of {} obstacles ({} draws each); lower the count or the clearances, or enlarge "
                     "the region",
                     placed.placed(), g.count, g.max_attempts));
  }
  spec.spheres.insert(spec.spheres.end(), placed.spheres.begin(), placed.spheres.end());
  spec.cylinders.insert(spec.cylinders.end(), placed.cylinders.begin(), placed.cylinders.end());
}

// Starts are points of the map: here only their place in the arena is checked. Whether an agent's sphere fits
// there depends on the game's radii, and the game checks it (game::Sim), once, before any run.
void Loader::check_starts(const MapSpec& spec) const {
  for (const StartRef& s : starts_) {
    if (const Problem p = check_start(s.position, spec.bounds)) fail(s.line, s.field, p.message);
  }
}

MapSpec Loader::load() {
  Node root;
  try {
    root = parse_yaml_text(read_input_file(file(), "map file"), file());
  } catch (const MapError&) {
    throw;
  } catch (const InputError& e) {
    fail(e.line(), e.field(), e.message());
  }
  if (!root.IsDefined() || root.IsNull()) fail(1, "", "the map file is empty");

  MapSpec spec;
  spec.source = file();
  const Fields top(*this, root, "");
  top.allow({"version", "name", "arena", "occupancy", "physics", "obstacles", "terrain", "movers", "random_obstacles",
             "start", "scenarios"});
  if (const Node* v = top.find("version")) {
    const long long version = integer(*v, "version");
    if (version != kFormatVersion) fail(*v, "version", fmt::format("unsupported map format version {} (this build reads {})", version, kFormatVersion));
  }
  if (const Node* v = top.find("name")) spec.name = text(*v, "name");
  read_arena(top.need("arena"), spec);
  read_occupancy(top.find("occupancy"), spec);

  const Node* start = top.find("start");
  const Node* scenarios = top.find("scenarios");
  if (start != nullptr && scenarios != nullptr) fail(*scenarios, "scenarios", "give either 'start' or 'scenarios', not both");
  if (start == nullptr && scenarios == nullptr) fail(root, "scenarios", "missing: give 'start' or 'scenarios'");
  if (start != nullptr) {
    spec.scenarios.push_back(read_scenario(*start, "start", "default"));
  } else {
    const Node& list = sequence(*scenarios, "scenarios");
    if (list.size() == 0) fail(list, "scenarios", "needs at least one scenario");
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string field = fmt::format("scenarios[{}]", i);
      Scenario s = read_scenario(list[i], field, "");
      if (spec.find_scenario(s.name) != nullptr) fail(list[i], field + ".name", fmt::format("duplicate scenario name '{}'", shown(s.name)));
      spec.scenarios.push_back(std::move(s));
    }
  }

  if (const Node* list = top.find("obstacles")) {
    sequence(*list, "obstacles");
    if (list->size() > std::size_t(kMaxObstacles)) {
      fail(*list, "obstacles", fmt::format("lists {} obstacles, more than the {} a map may hold", list->size(), kMaxObstacles));
    }
    for (std::size_t i = 0; i < list->size(); ++i) read_obstacle((*list)[i], fmt::format("obstacles[{}]", i), spec);
  }
  if (const Node* list = top.find("terrain")) {
    sequence(*list, "terrain");
    for (std::size_t i = 0; i < list->size(); ++i) read_terrain((*list)[i], fmt::format("terrain[{}]", i), spec);
  }
  check_starts(spec);
  if (const Node* n = top.find("physics")) read_physics(*n, spec);
  if (const Node* list = top.find("movers")) {
    sequence(*list, "movers");
    if (list->size() > std::size_t(kMaxMovers)) {
      fail(*list, "movers", fmt::format("lists {} movers, more than the {} a map may hold", list->size(), kMaxMovers));
    }
    for (std::size_t i = 0; i < list->size(); ++i) read_mover((*list)[i], fmt::format("movers[{}]", i), spec);
  }
  if (const Node* list = top.find("random_obstacles")) {
    sequence(*list, "random_obstacles");
    for (std::size_t i = 0; i < list->size(); ++i) read_generator((*list)[i], fmt::format("random_obstacles[{}]", i), spec);
  }
  if (!spec.movers.empty()) {
    std::vector<TriangleMesh> meshes;
    for (const TerrainMesh& t : spec.meshes) meshes.push_back(*t.imported);
    validate_movers(spec, meshes);
  }
  return spec;
}

}  // namespace

MapSpec load_map(const std::filesystem::path& file) {
  try {
    return Loader(file).load();
  } catch (const YAML::Exception& e) {
    // Every check above fails with a MapError; this is a backstop for yaml-cpp's own surprises.
    throw MapError(file, e.mark.line >= 0 ? e.mark.line + 1 : 0, "", e.msg);
  }
}

}  // namespace peg3d::world
