#include "game/observation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "game/sim.hpp"

namespace peg3d::game {

std::pair<double, double> entry_bounds(EntryRange range, const Box& box, double reach, double speed) {
  const Vec3 extent = box.hi - box.lo;
  switch (range) {
    case EntryRange::kDistance: return {0.0, reach};
    case EntryRange::kAngle: return {-kPi, kPi};
    case EntryRange::kPolar: return {0.0, kPi};
    case EntryRange::kPositionX: return {box.lo.x(), box.hi.x()};
    case EntryRange::kPositionY: return {box.lo.y(), box.hi.y()};
    case EntryRange::kPositionZ: return {box.lo.z(), box.hi.z()};
    case EntryRange::kOffsetX: return {-extent.x(), extent.x()};
    case EntryRange::kOffsetY: return {-extent.y(), extent.y()};
    case EntryRange::kOffsetZ: return {-extent.z(), extent.z()};
    case EntryRange::kVelocity: return {-speed, speed};
    case EntryRange::kReach: return {-reach, reach};
  }
  return {0.0, 0.0};
}

void observation_base(const AgentView& v, float* o) {
  const Percept& p = v.percept;
  const Vec3& self = v.self.position;
  const Vec3 rel = v.other.position - self;
  const Vec3 vel = v.other_speed * direction(v.other.heading);
  const Vec3 obstacle = v.field.found ? Vec3(v.field.point - self) : Vec3::Zero();
  const double x[kObservationBase] = {
      p.target_distance,  p.target.azimuth,    p.target.elevation, p.obstacle.distance, p.to_obstacle.azimuth,
      p.to_obstacle.elevation, self.x(),       self.y(),           self.z(),            v.self.heading.alpha,
      v.self.heading.theta, rel.x(),           rel.y(),            rel.z(),             vel.x(),
      vel.y(),            vel.z(),             obstacle.x(),       obstacle.y(),        obstacle.z()};
  for (int k = 0; k < kObservationBase; ++k) o[k] = static_cast<float>(x[k]);
}

const sense::Segment* ObservationTable::find(std::string_view name) const {
  for (const sense::Segment& s : segments) {
    if (s.name == name) return &s;
  }
  return nullptr;
}

namespace {

// "1st", "2nd", "3rd", "4th", ... for the neighbour slots' meanings.
std::string ordinal(int n) {
  const int last = n % 10, tens = n % 100;
  const char* suffix = (tens >= 11 && tens <= 13) ? "th" : last == 1 ? "st" : last == 2 ? "nd" : last == 3 ? "rd" : "th";
  return fmt::format("{}{}", n, suffix);
}

// The fastest agent of the configuration (m/s): what bounds an opponent's velocity.
double fastest(const GameConfig& c) {
  double speed = std::max(c.pursuer.speed, c.evader.speed);
  for (const auto& a : c.pursuers) speed = std::max(speed, a.speed);
  for (const auto& a : c.evaders) speed = std::max(speed, a.speed);
  return speed;
}

// Float rounding of a bound must not exclude a value rounded the other way: each widened by one ulp.
void widen(sense::Segment& s) {
  for (float& lo : s.low) lo = std::nextafter(lo, -INFINITY);
  for (float& hi : s.high) hi = std::nextafter(hi, INFINITY);
}

}  // namespace

ObservationTable observation_table(const Sim& sim, Role role, int rank, int neighbours) {
  if (neighbours < 0 || neighbours > kMaxNeighbours) {
    throw std::invalid_argument(fmt::format("neighbours: {} is not in [0, {}]", neighbours, kMaxNeighbours));
  }
  const Box& box = sim.arena().bounds();
  const Vec3 extent = box.hi - box.lo;
  const double reach = std::max(extent.norm(), sim.arena().max_distance());
  ObservationTable t;
  t.neighbours = neighbours;
  for (const ObservationEntry& e : kObservationEntries) {
    const auto [lo, hi] = entry_bounds(e.range, box, reach, fastest(sim.config()));
    t.segments.push_back(sense::Segment::uniform(e.name, 1, e.unit, lo, hi, e.meaning));
  }
  for (const char* kind : {"opponent", "teammate"}) {
    for (int m = 0; m < neighbours; ++m) {
      sense::Segment offset = sense::Segment::uniform(
          fmt::format("neighbour.{}.{}.offset", kind, m), 3, "m", 0.0, 0.0,
          fmt::format("the position of the agent's {} nearest other {} still in the game (nearest first) minus its own "
                      "(0 when there is none)",
                      ordinal(m + 1), kind));
      for (int a = 0; a < 3; ++a) offset.low[std::size_t(a)] = float(-extent[a]), offset.high[std::size_t(a)] = float(extent[a]);
      t.segments.push_back(std::move(offset));
      t.segments.push_back(sense::Segment::uniform(fmt::format("neighbour.{}.{}.mask", kind, m), 1, "", 0.0, 1.0,
                                                   fmt::format("1 when that {} is there, 0 when the slot is empty (fewer {}s than slots)", kind, kind)));
    }
  }
  const sense::SegmentContext context{sim.config().time_limit};
  const auto sensors = sim.sensors(role, rank);
  for (std::size_t k = 0; k < sensors.size(); ++k) {
    const std::size_t before = t.segments.size();
    sensors[k]->segments(context, t.segments);
    int size = 0;
    for (std::size_t s = before; s < t.segments.size(); ++s) size += t.segments[s].size;
    if (size > 0) t.sensors.push_back({int(k), 0, size});
  }
  sense::lay_out(t.segments);
  for (sense::Segment& s : t.segments) widen(s);
  // Each sensor's entries start where its first segment does.
  int at = kObservationBase + 8 * neighbours;
  for (ObservationTable::SensorPart& p : t.sensors) {
    p.offset = at;
    at += p.size;
  }
  return t;
}

ObservationTable bind_observation(const Sim& sim, Role role, int rank, std::span<const sense::Segment> recorded) {
  int neighbours = 0;
  for (const sense::Segment& s : recorded) {
    neighbours += s.name.starts_with("neighbour.opponent.") && s.name.ends_with(".mask");
  }
  ObservationTable own = observation_table(sim, role, rank, std::min(neighbours, kMaxNeighbours));
  if (const auto difference = sense::first_difference(recorded, own.segments)) throw std::invalid_argument(*difference);
  return own;
}

void write_observation(const Sim& sim, const SimState& st, int i, const ObservationTable& table, std::span<float> out) {
  (void)sim;
  const AgentState& a = st.agents[std::size_t(i)];
  const AgentView& v = a.view;
  observation_base(v, out.data());
  const Vec3& self = v.self.position;
  float* slot = out.data() + kObservationBase;
  // Where agent i takes agent j to be: an opponent as its sight knows it, a teammate as it is.
  const auto known = [&](int j) {
    return st.agents[std::size_t(j)].role != a.role ? st.known_state(i, j).position : st.agents[std::size_t(j)].kinematics.position;
  };
  // The k nearest other opponents, then the k nearest teammates, still in the game.
  if (table.neighbours > 0) {
    const int n = st.agent_count();
    for (const bool opponents : {true, false}) {
      std::array<std::pair<double, int>, 2 * world::kMaxAgentsPerRole> near{};
      int count = 0;
      for (int j = 0; j < n; ++j) {
        const AgentState& b = st.agents[std::size_t(j)];
        if (j == i || !b.active || (b.role != a.role) != opponents || (opponents && j == a.opponent)) continue;
        near[std::size_t(count++)] = {(known(j) - self).squaredNorm(), j};
      }
      std::sort(near.begin(), near.begin() + count);  // by distance, then index: deterministic
      for (int k = 0; k < table.neighbours; ++k, slot += 4) {
        if (k < count) {
          const Vec3 d = known(near[std::size_t(k)].second) - self;
          slot[0] = float(d.x()), slot[1] = float(d.y()), slot[2] = float(d.z()), slot[3] = 1.0f;
        } else {
          slot[0] = slot[1] = slot[2] = slot[3] = 0.0f;
        }
      }
    }
  }
  const std::span<const sense::Reading> readings = st.readings(i);
  const sense::ObserveContext context{v.other_visible, v.other_age};
  for (const ObservationTable::SensorPart& p : table.sensors) {
    const sense::Reading& r = readings[std::size_t(p.sensor)];
    r.sensor->observe(r, context, out.subspan(std::size_t(p.offset), std::size_t(p.size)));
  }
}

namespace {

class StateObservationWriter final : public ObservationWriter {
 public:
  void write(int agent, const ObservationTable& table, std::span<float> out) const override {
    write_observation(*sim, *state, agent, table, out);
  }
  ObservationTable bind(int agent, std::span<const sense::Segment> recorded) const override {
    const AgentState& a = state->agents[std::size_t(agent)];
    return bind_observation(*sim, a.role, a.rank, recorded);
  }
  const void* model() const override { return sim; }
  const Sim* sim = nullptr;
  const SimState* state = nullptr;
};

}  // namespace

void attach_observation_writer(const Sim& sim, SimState& st) {
  if (!st.observation_writer) st.observation_writer = std::make_unique<StateObservationWriter>();
  auto& w = static_cast<StateObservationWriter&>(*st.observation_writer);
  w.sim = &sim, w.state = &st;  // the Sim this reset plays, and the state where it lives now
}

}  // namespace peg3d::game
