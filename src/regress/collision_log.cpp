#include "regress/collision_log.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <sstream>

#include <fmt/format.h>

#include "core/error.hpp"
#include "core/hash.hpp"
#include "world/map/movers.hpp"

namespace peg3d::regress {
namespace {

std::string v3(const Vec3& v) { return fmt::format("{:.6f},{:.6f},{:.6f}", v.x(), v.y(), v.z()); }
std::string v3_text(const Vec3& v) { return fmt::format("({:.6f}, {:.6f}, {:.6f})", v.x(), v.y(), v.z()); }

std::string hit_of(const game::Trace& trace, const game::CollisionEvent& e) {
  if (e.kind == world::ObstacleKind::kAgent) return "agent:" + game::agent_label(trace, e.obstacle_id);
  return fmt::format("{}:{}", world::to_string(e.kind), e.obstacle_id);
}

}  // namespace

CollisionLog make_log(const std::string& name, const game::Trace& trace, const game::SimState& st,
                      const world::MoverTimeline* movers) {
  CollisionLog log;
  log.name = name;
  log.outcome = game::to_string(st.outcome);
  log.steps = st.step;
  log.time = st.time;
  for (const game::CollisionEvent& e : trace.collisions) {
    log.events.push_back({e.step, e.time, game::agent_label(trace, e.agent), hit_of(trace, e), e.triangle, e.point, e.normal,
                          e.penetration});
  }
  for (const game::CaptureEvent& c : trace.captures) {
    log.captures.push_back({c.step, c.time, game::agent_label(trace, c.pursuer), game::agent_label(trace, c.evader), c.distance});
  }
  for (int i = 0; i < st.agent_count(); ++i) {
    const game::AgentState& a = st.agents[std::size_t(i)];
    log.agents.push_back({game::agent_label(trace, i), a.kinematics.position, a.kinematics.heading.alpha,
                          a.kinematics.heading.theta, a.path, a.active});
  }
  for (const game::PushEvent& p : trace.pushes) {
    log.pushes.push_back({p.step, p.time, game::agent_label(trace, p.agent), p.obstacle_id, p.point, p.normal});
  }
  if (movers != nullptr) {
    for (int m = 0; m < movers->count(); ++m) {
      const Pose p = st.push && !movers->mover(m).kinematic() ? st.push->pose(m) : movers->pose(m, st.time);
      log.movers.push_back({m, to_string(movers->mover(m).shape.kind), p.position, p.orientation});
    }
  }
  Fnv1a h;
  for (int k = 0; k < trace.frame_count(); ++k) {
    for (int i = 0; i < trace.agents; ++i) {
      const game::AgentFrame& f = trace.at(k, i);
      h.add_value(f.state.position.x());
      h.add_value(f.state.position.y());
      h.add_value(f.state.position.z());
      h.add_value(f.state.heading.alpha);
      h.add_value(f.state.heading.theta);
    }
  }
  log.trajectory_hash = h.value();
  return log;
}

std::string format_log(const CollisionLog& log) {
  std::string out = "# peg3d collision log, format 2 (docs/collision-tests.md)\n";
  out += fmt::format("case {}\n", log.name);
  out += fmt::format("outcome {} steps={} time={:.6f}\n", log.outcome, log.steps, log.time);
  for (std::size_t i = 0; i < log.events.size(); ++i) {
    const LoggedEvent& e = log.events[i];
    out += fmt::format("event {} step={} time={:.6f} agent={} hit={} triangle={} point={} normal={} penetration={:.6f}\n",
                       i + 1, e.step, e.time, e.agent, e.hit, e.triangle < 0 ? std::string("-") : std::to_string(e.triangle),
                       v3(e.point), v3(e.normal), e.penetration);
  }
  for (std::size_t i = 0; i < log.captures.size(); ++i) {
    const LoggedCapture& c = log.captures[i];
    out += fmt::format("capture {} step={} time={:.6f} pursuer={} evader={} distance={:.6f}\n", i + 1, c.step, c.time,
                       c.pursuer, c.evader, c.distance);
  }
  for (std::size_t i = 0; i < log.pushes.size(); ++i) {
    const LoggedPush& p = log.pushes[i];
    out += fmt::format("push {} step={} time={:.6f} agent={} body=mover:{} point={} normal={}\n", i + 1, p.step, p.time,
                       p.agent, p.mover, v3(p.point), v3(p.normal));
  }
  for (const LoggedAgent& a : log.agents) {
    out += fmt::format("agent {} position={} alpha={:.6f} theta={:.6f} path={:.6f} active={}\n", a.label, v3(a.position),
                       a.alpha, a.theta, a.path, a.active ? "yes" : "no");
  }
  for (const LoggedMover& m : log.movers) {
    out += fmt::format("mover {} kind={} position={} orientation={:.6f},{:.6f},{:.6f},{:.6f}\n", m.id, m.kind,
                       v3(m.position), m.orientation.w(), m.orientation.x(), m.orientation.y(), m.orientation.z());
  }
  out += fmt::format("trajectory {:#018x}\n", log.trajectory_hash);
  return out;
}

namespace {

// One record's fields: the type, its label (event number, agent label, ...) and key=value pairs.
struct Record {
  std::string type, label;
  std::map<std::string, std::string> fields;
};

class Reader {
 public:
  Reader(const std::filesystem::path& file, int line) : file_(file), line_(line) {}

  [[noreturn]] void fail(const std::string& field, const std::string& message) const {
    throw InputError(file_, line_, field, message);
  }
  const std::string& need(const Record& r, const std::string& key) const {
    const auto it = r.fields.find(key);
    if (it == r.fields.end()) fail(r.type + "." + key, "missing");
    return it->second;
  }
  double number(const Record& r, const std::string& key) const {
    const std::string& s = need(r, key);
    char* end = nullptr;
    const double v = std::strtod(s.c_str(), &end);
    if (end == s.c_str() || *end != '\0' || !std::isfinite(v)) fail(r.type + "." + key, "'" + s + "' is not a number");
    return v;
  }
  int integer(const std::string& s, const std::string& field) const {
    char* end = nullptr;
    const long v = std::strtol(s.c_str(), &end, 10);
    if (end == s.c_str() || *end != '\0' || v < -1 || v > 1000000000) fail(field, "'" + s + "' is not a count");
    return static_cast<int>(v);
  }
  std::vector<double> numbers(const Record& r, const std::string& key, std::size_t n) const {
    std::vector<double> out;
    std::stringstream in(need(r, key));
    std::string item;
    while (std::getline(in, item, ',')) {
      char* end = nullptr;
      const double v = std::strtod(item.c_str(), &end);
      if (end == item.c_str() || *end != '\0' || !std::isfinite(v)) fail(r.type + "." + key, "'" + item + "' is not a number");
      out.push_back(v);
    }
    if (out.size() != n) fail(r.type + "." + key, fmt::format("needs {} numbers, got {}", n, out.size()));
    return out;
  }
  Vec3 vec(const Record& r, const std::string& key) const {
    const auto v = numbers(r, key, 3);
    return {v[0], v[1], v[2]};
  }

 private:
  const std::filesystem::path& file_;
  int line_;
};

}  // namespace

// Logs of format 1 (before issue 37) named agents by the labels of then; each is read as its current label
// (game::current_agent_label), so that an old golden log still compares equal to a new run.
CollisionLog parse_log(std::string_view text, const std::filesystem::path& file) {
  CollisionLog log;
  bool have_case = false, have_outcome = false, have_hash = false;
  std::stringstream in{std::string(text)};
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty() || line.front() == '#') continue;
    std::stringstream words(line);
    Record r;
    words >> r.type;
    const Reader reader(file, number);
    const bool labelled = r.type == "event" || r.type == "capture" || r.type == "push" || r.type == "agent" || r.type == "mover" ||
                          r.type == "case" || r.type == "outcome" || r.type == "trajectory";
    if (!labelled) reader.fail("", "unknown record '" + r.type + "'");
    words >> r.label;
    if (r.label.empty()) reader.fail(r.type, "has no value");
    std::string token;
    while (words >> token) {
      const std::size_t eq = token.find('=');
      if (eq == std::string::npos || eq == 0) reader.fail(r.type, "'" + token + "' is not key=value");
      r.fields[token.substr(0, eq)] = token.substr(eq + 1);
    }
    if (r.type == "case") {
      log.name = r.label;
      have_case = true;
    } else if (r.type == "outcome") {
      log.outcome = r.label;
      log.steps = reader.integer(reader.need(r, "steps"), "outcome.steps");
      log.time = reader.number(r, "time");
      have_outcome = true;
    } else if (r.type == "event") {
      LoggedEvent e;
      e.step = reader.integer(reader.need(r, "step"), "event.step");
      e.time = reader.number(r, "time");
      e.agent = game::current_agent_label(reader.need(r, "agent"));
      e.hit = reader.need(r, "hit");
      if (e.hit.starts_with("agent:")) e.hit = "agent:" + game::current_agent_label(e.hit.substr(6));
      const std::string& tri = reader.need(r, "triangle");
      e.triangle = tri == "-" ? -1 : reader.integer(tri, "event.triangle");
      e.point = reader.vec(r, "point");
      e.normal = reader.vec(r, "normal");
      e.penetration = reader.number(r, "penetration");
      log.events.push_back(e);
    } else if (r.type == "capture") {
      log.captures.push_back({reader.integer(reader.need(r, "step"), "capture.step"), reader.number(r, "time"),
                              game::current_agent_label(reader.need(r, "pursuer")),
                              game::current_agent_label(reader.need(r, "evader")), reader.number(r, "distance")});
    } else if (r.type == "push") {
      LoggedPush p;
      p.step = reader.integer(reader.need(r, "step"), "push.step");
      p.time = reader.number(r, "time");
      p.agent = game::current_agent_label(reader.need(r, "agent"));
      const std::string& body = reader.need(r, "body");
      if (body.rfind("mover:", 0) != 0) reader.fail("push.body", "'" + body + "' is not mover:<index>");
      p.mover = reader.integer(body.substr(6), "push.body");
      p.point = reader.vec(r, "point");
      p.normal = reader.vec(r, "normal");
      log.pushes.push_back(p);
    } else if (r.type == "agent") {
      const std::string& active = reader.need(r, "active");
      if (active != "yes" && active != "no") reader.fail("agent.active", "must be yes or no");
      log.agents.push_back({game::current_agent_label(r.label), reader.vec(r, "position"), reader.number(r, "alpha"), reader.number(r, "theta"),
                            reader.number(r, "path"), active == "yes"});
    } else if (r.type == "mover") {
      const auto q = reader.numbers(r, "orientation", 4);
      log.movers.push_back({reader.integer(r.label, "mover"), reader.need(r, "kind"), reader.vec(r, "position"),
                            Quat(q[0], q[1], q[2], q[3])});
    } else {
      char* end = nullptr;
      log.trajectory_hash = std::strtoull(r.label.c_str(), &end, 16);
      if (end == r.label.c_str() || *end != '\0') reader.fail("trajectory", "'" + r.label + "' is not a hexadecimal hash");
      have_hash = true;
    }
  }
  if (!have_case || !have_outcome || !have_hash) {
    throw InputError(file, 0, "", "not a collision log (it needs case, outcome and trajectory records)");
  }
  return log;
}

namespace {

std::string seconds(double t) { return fmt::format("{:.6f} s", t); }
std::string metres(double d) { return fmt::format("{:.6f} m", d); }
std::string quat_text(const Quat& q) { return fmt::format("(w {:.6f}, {:.6f}, {:.6f}, {:.6f})", q.w(), q.x(), q.y(), q.z()); }

bool differs(double x, double y, double t) { return std::abs(x - y) > t; }

using Differences = std::vector<std::string>;

// What a collision event and a push have alike: the step, the time, the point and the normal.
template <class Touch>
void compare_touch(const std::string& where, const Touch& x, const Touch& y, const Tolerances& tol, Differences& d) {
  if (x.step != y.step) d.push_back(fmt::format("{}: step {} -> {}", where, x.step, y.step));
  if (differs(x.time, y.time, tol.time)) d.push_back(fmt::format("{}: time {} -> {}", where, seconds(x.time), seconds(y.time)));
  if ((x.point - y.point).norm() > tol.length) {
    d.push_back(fmt::format("{}: point {} -> {}", where, v3_text(x.point), v3_text(y.point)));
  }
  if ((x.normal - y.normal).norm() > tol.unit) {
    d.push_back(fmt::format("{}: normal {} -> {}", where, v3_text(x.normal), v3_text(y.normal)));
  }
}

void compare_events(const CollisionLog& e, const CollisionLog& a, const Tolerances& tol, Differences& d) {
  const std::size_t events = std::max(e.events.size(), a.events.size());
  for (std::size_t i = 0; i < events; ++i) {
    const std::string where = fmt::format("event {}", i + 1);
    if (i >= a.events.size()) {
      d.push_back(fmt::format("{}: {} hit {} at {} -> (none)", where, e.events[i].agent, e.events[i].hit, seconds(e.events[i].time)));
      continue;
    }
    if (i >= e.events.size()) {
      d.push_back(fmt::format("{}: (none) -> {} hit {} at {}", where, a.events[i].agent, a.events[i].hit, seconds(a.events[i].time)));
      continue;
    }
    const LoggedEvent& x = e.events[i];
    const LoggedEvent& y = a.events[i];
    if (x.agent != y.agent) d.push_back(fmt::format("{}: agent {} -> {}", where, x.agent, y.agent));
    if (x.hit != y.hit) d.push_back(fmt::format("{}: hit {} -> {}", where, x.hit, y.hit));
    if (x.triangle != y.triangle) d.push_back(fmt::format("{}: triangle {} -> {}", where, x.triangle, y.triangle));
    compare_touch(where, x, y, tol, d);
    if (differs(x.penetration, y.penetration, tol.length)) {
      d.push_back(fmt::format("{}: penetration {} -> {}", where, metres(x.penetration), metres(y.penetration)));
    }
  }
}

void compare_captures(const CollisionLog& e, const CollisionLog& a, const Tolerances& tol, Differences& d) {
  const std::size_t captures = std::max(e.captures.size(), a.captures.size());
  for (std::size_t i = 0; i < captures; ++i) {
    const std::string where = fmt::format("capture {}", i + 1);
    if (i >= a.captures.size() || i >= e.captures.size()) {
      const bool gone = i >= a.captures.size();
      const LoggedCapture& c = gone ? e.captures[i] : a.captures[i];
      const std::string text = fmt::format("{} caught {} at {}", c.pursuer, c.evader, seconds(c.time));
      d.push_back(gone ? fmt::format("{}: {} -> (none)", where, text) : fmt::format("{}: (none) -> {}", where, text));
      continue;
    }
    const LoggedCapture& x = e.captures[i];
    const LoggedCapture& y = a.captures[i];
    if (x.pursuer != y.pursuer || x.evader != y.evader) {
      d.push_back(fmt::format("{}: {} caught {} -> {} caught {}", where, x.pursuer, x.evader, y.pursuer, y.evader));
    }
    if (x.step != y.step) d.push_back(fmt::format("{}: step {} -> {}", where, x.step, y.step));
    if (differs(x.time, y.time, tol.time)) d.push_back(fmt::format("{}: time {} -> {}", where, seconds(x.time), seconds(y.time)));
    if (differs(x.distance, y.distance, tol.length)) {
      d.push_back(fmt::format("{}: distance {} -> {}", where, metres(x.distance), metres(y.distance)));
    }
  }
}

void compare_pushes(const CollisionLog& e, const CollisionLog& a, const Tolerances& tol, Differences& d) {
  if (e.pushes.size() != a.pushes.size()) d.push_back(fmt::format("pushes {} -> {}", e.pushes.size(), a.pushes.size()));
  for (std::size_t i = 0; i < std::min(e.pushes.size(), a.pushes.size()); ++i) {
    const LoggedPush& x = e.pushes[i];
    const LoggedPush& y = a.pushes[i];
    const std::string where = fmt::format("push {}", i + 1);
    if (x.agent != y.agent || x.mover != y.mover) {
      d.push_back(fmt::format("{}: {} pushed mover {} -> {} pushed mover {}", where, x.agent, x.mover, y.agent, y.mover));
    }
    compare_touch(where, x, y, tol, d);
  }
}

void compare_agents(const CollisionLog& e, const CollisionLog& a, const Tolerances& tol, Differences& d) {
  if (e.agents.size() != a.agents.size()) d.push_back(fmt::format("agents {} -> {}", e.agents.size(), a.agents.size()));
  for (std::size_t i = 0; i < std::min(e.agents.size(), a.agents.size()); ++i) {
    const LoggedAgent& x = e.agents[i];
    const LoggedAgent& y = a.agents[i];
    const std::string where = "agent " + x.label;
    if (x.label != y.label) d.push_back(fmt::format("agent {}: label -> {}", x.label, y.label));
    if ((x.position - y.position).norm() > tol.length) {
      d.push_back(fmt::format("{}: final position {} -> {}", where, v3_text(x.position), v3_text(y.position)));
    }
    if (differs(x.alpha, y.alpha, tol.angle) || differs(x.theta, y.theta, tol.angle)) {
      d.push_back(fmt::format("{}: final heading ({:.6f}, {:.6f}) -> ({:.6f}, {:.6f}) rad", where, x.alpha, x.theta, y.alpha, y.theta));
    }
    if (differs(x.path, y.path, tol.length)) d.push_back(fmt::format("{}: path {} -> {}", where, metres(x.path), metres(y.path)));
    if (x.active != y.active) d.push_back(fmt::format("{}: in the game {} -> {}", where, x.active ? "yes" : "no", y.active ? "yes" : "no"));
  }
}

void compare_movers(const CollisionLog& e, const CollisionLog& a, const Tolerances& tol, Differences& d) {
  if (e.movers.size() != a.movers.size()) d.push_back(fmt::format("movers {} -> {}", e.movers.size(), a.movers.size()));
  for (std::size_t i = 0; i < std::min(e.movers.size(), a.movers.size()); ++i) {
    const LoggedMover& x = e.movers[i];
    const LoggedMover& y = a.movers[i];
    const std::string where = fmt::format("mover {}", x.id);
    if (x.kind != y.kind) d.push_back(fmt::format("{}: kind {} -> {}", where, x.kind, y.kind));
    if ((x.position - y.position).norm() > tol.length) {
      d.push_back(fmt::format("{}: final position {} -> {}", where, v3_text(x.position), v3_text(y.position)));
    }
    // q and -q are the same rotation.
    const double turned = std::min((x.orientation.coeffs() - y.orientation.coeffs()).norm(),
                                   (x.orientation.coeffs() + y.orientation.coeffs()).norm());
    if (turned > tol.unit) {
      d.push_back(fmt::format("{}: final orientation {} -> {}", where, quat_text(x.orientation), quat_text(y.orientation)));
    }
  }
}

}  // namespace

std::vector<std::string> compare_logs(const CollisionLog& e, const CollisionLog& a, const Tolerances& tol, bool strict,
                                      std::vector<std::string>* notes) {
  Differences d;
  if (e.outcome != a.outcome) d.push_back(fmt::format("outcome {} -> {}", e.outcome, a.outcome));
  if (e.steps != a.steps) d.push_back(fmt::format("steps {} -> {}", e.steps, a.steps));
  if (differs(e.time, a.time, tol.time)) d.push_back(fmt::format("end time {} -> {}", seconds(e.time), seconds(a.time)));
  compare_events(e, a, tol, d);
  compare_captures(e, a, tol, d);
  compare_pushes(e, a, tol, d);
  compare_agents(e, a, tol, d);
  compare_movers(e, a, tol, d);
  if (e.trajectory_hash != a.trajectory_hash) {
    const std::string text = fmt::format("trajectory hash {:#018x} -> {:#018x}", e.trajectory_hash, a.trajectory_hash);
    if (strict) {
      d.push_back(text);
    } else if (notes != nullptr) {
      notes->push_back(text + " (the trajectory moved below the tolerances)");
    }
  }
  return d;
}

}  // namespace peg3d::regress
