#include "results/trajectory_file.hpp"

#include <charconv>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/input_files.hpp"
#include "geometry/angles.hpp"
#include "results/csv_writer.hpp"

namespace peg3d::results {
namespace {

// The per-agent columns after the position and heading groups, in file order.
constexpr const char* kAgentColumns[] = {"d_target", "target_az",   "target_el", "d_obstacle", "obstacle_az",
                                         "obstacle_el", "d_alpha", "d_theta",   "reward",     "pinned"};

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t from = 0;
  for (;;) {
    const std::size_t comma = line.find(',', from);
    out.push_back(line.substr(from, comma == std::string_view::npos ? std::string_view::npos : comma - from));
    if (comma == std::string_view::npos) return out;
    from = comma + 1;
  }
}

std::optional<world::ObstacleKind> kind_named(std::string_view name) {
  for (auto k : {world::ObstacleKind::kSphere, world::ObstacleKind::kCylinder, world::ObstacleKind::kMesh,
                 world::ObstacleKind::kBoundary, world::ObstacleKind::kAgent, world::ObstacleKind::kMover}) {
    if (name == world::to_string(k)) return k;
  }
  return std::nullopt;
}

std::vector<std::string_view> split_lines(const std::string& text) {
  std::vector<std::string_view> lines;
  for (std::size_t from = 0; from < text.size();) {
    const std::size_t end = text.find('\n', from);
    std::string_view line(text.data() + from, (end == std::string::npos ? text.size() : end) - from);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    lines.push_back(line);
    from = end == std::string::npos ? text.size() : end + 1;
  }
  return lines;
}

// Reads a trajectory file's rows into a trace, with the columns its header names.
class TrajectoryReader {
 public:
  /// Reads the header line: the agents (in column order of their positions, pursuers first) and where each
  /// of their columns is.
  TrajectoryReader(const std::filesystem::path& file, std::string_view header_line) : file_(file) {
    header_ = split(header_line);
    for (std::size_t c = 0; c < header_.size(); ++c) {
      if (!column_.emplace(std::string(header_[c]), c).second) {
        throw InputError(file_, 1, std::string(header_[c]), "column appears twice");
      }
    }
    if (header_.front() != "t") throw InputError(file_, 1, "t", "the first column must be t: not a trajectory file");
    read_agents();
    cols_.resize(labels_.size());
    for (std::size_t i = 0; i < labels_.size(); ++i) {
      const std::string& l = labels_[i];
      cols_[i].pos[0] = need(l + "_x"), cols_[i].pos[1] = need(l + "_y"), cols_[i].pos[2] = need(l + "_z");
      cols_[i].heading[0] = need(l + "_alpha"), cols_[i].heading[1] = need(l + "_theta");
      for (std::size_t v = 0; v < std::size(kAgentColumns); ++v) cols_[i].values[v] = need(l + "_" + kAgentColumns[v]);
      cols_[i].active = optional(l + "_active");
      cols_[i].hit = optional(l + "_hit");
      cols_[i].captured = optional(l + "_captured");
    }
  }

  /// Appends the instant of one row (line `line_no` of the file): every agent's frame, its collision and the
  /// captures.
  void read_row(int line_no, std::string_view line) {
    fields_ = split(line);
    line_ = line_no;
    if (fields_.size() != header_.size()) {
      throw InputError(file_, line_no, "", fmt::format("{} fields where the header has {}", fields_.size(), header_.size()));
    }
    const int k = trace_.frame_count();
    const double t = number(0);
    if (!std::isfinite(t) || (k > 0 && !(t > trace_.times.back()))) {
      throw InputError(file_, line_no, "t", "times must be finite and increase from row to row");
    }
    trace_.times.push_back(t);
    for (std::size_t i = 0; i < labels_.size(); ++i) trace_.frames.push_back(read_frame(i, k, t));
    read_captures(k, t);
  }

  game::Trace take() { return std::move(trace_); }

 private:
  struct AgentColumns {
    std::size_t pos[3], heading[2], values[std::size(kAgentColumns)];
    std::optional<std::size_t> active, hit, captured;
  };

  // The agents: the position columns come first after t, three per agent.
  void read_agents() {
    for (std::size_t c = 1; c < header_.size(); c += 3) {
      const std::string_view h = header_[c];
      if (h.size() < 3 || !h.ends_with("_x")) break;
      const std::string label(h.substr(0, h.size() - 2));
      const bool pursuer = label.starts_with("pursuer"), evader = label.starts_with("evader");
      if (!pursuer && !evader) throw InputError(file_, 1, std::string(h), "an agent's label starts with pursuer or evader");
      labels_.push_back(label);
      trace_.roles.push_back(pursuer ? game::Role::kPursuer : game::Role::kEvader);
    }
    if (labels_.empty()) throw InputError(file_, 1, "", "no agent columns (<agent>_x, _y, _z) after t");
    bool pursuers_seen = false, evaders_seen = false;
    for (std::size_t i = 0; i < labels_.size(); ++i) {
      const bool p = trace_.roles[i] == game::Role::kPursuer;
      if (p && evaders_seen) throw InputError(file_, 1, labels_[i] + "_x", "pursuers come before evaders");
      (p ? pursuers_seen : evaders_seen) = true;
    }
    if (!pursuers_seen || !evaders_seen) throw InputError(file_, 1, "", "needs at least one pursuer and one evader");
    trace_.agents = static_cast<int>(labels_.size());
  }

  std::size_t need(const std::string& name) const {
    const auto it = column_.find(name);
    if (it == column_.end()) throw InputError(file_, 1, name, "missing column");
    return it->second;
  }
  std::optional<std::size_t> optional(const std::string& name) const {
    const auto it = column_.find(name);
    return it == column_.end() ? std::nullopt : std::optional<std::size_t>(it->second);
  }

  double number(std::size_t c) const {
    double v = 0.0;
    const std::string_view s = fields_[c];
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (s.empty() || ec != std::errc() || end != s.data() + s.size()) {
      throw InputError(file_, line_, std::string(header_[c]), "'" + shown(std::string(s)) + "' is not a number");
    }
    return v;
  }

  // Agent i's frame at instant k (time t), and its collision there, if the row says it hit something.
  game::AgentFrame read_frame(std::size_t i, int k, double t) {
    const AgentColumns& c = cols_[i];
    game::AgentFrame a;
    a.state.position = Vec3(number(c.pos[0]), number(c.pos[1]), number(c.pos[2]));
    if (!a.state.position.allFinite()) throw InputError(file_, line_, labels_[i] + "_x", "positions must be finite");
    a.state.heading = {number(c.heading[0]), number(c.heading[1])};
    double v[std::size(kAgentColumns)];
    for (std::size_t j = 0; j < std::size(kAgentColumns); ++j) v[j] = number(c.values[j]);
    game::Percept& q = a.percept;
    q.target_distance = v[0];
    q.target = {v[1], v[2]};
    q.obstacle.distance = v[3];
    q.to_obstacle = {v[4], v[5]};
    // Nothing in range reads as the errors (pi, 0) at the field's cap; anything else points at the obstacle.
    q.obstacle.found = std::isfinite(v[3]) && !(v[4] == kPi && v[5] == 0.0);
    if (q.obstacle.found) {
      q.obstacle.point = a.state.position + v[3] * direction({a.state.heading.alpha + v[4], a.state.heading.theta + v[5]});
    }
    a.command = {v[6], v[7]};
    a.reward = v[8];
    q.pinned = v[9] != 0.0;
    a.active = !c.active || number(*c.active) != 0.0;
    if (c.hit && !fields_[*c.hit].empty()) {
      const auto kind = kind_named(fields_[*c.hit]);
      if (!kind) {
        throw InputError(file_, line_, labels_[i] + "_hit", "'" + shown(std::string(fields_[*c.hit])) + "' is not an obstacle kind");
      }
      game::CollisionEvent e;
      e.step = k, e.time = t, e.agent = static_cast<int>(i), e.role = trace_.roles[i], e.kind = *kind;
      e.point = a.state.position;
      trace_.collisions.push_back(e);
    }
    return a;
  }

  // A capture at instant k, by the nearest pursuer (as the game picks it); files without the _captured column
  // tell it by the evader leaving the game, which misses the capture that ends the episode.
  void read_captures(int k, double t) {
    const std::size_t n = labels_.size();
    for (std::size_t e = 0; e < n && k > 0; ++e) {
      if (trace_.roles[e] != game::Role::kEvader) continue;
      const bool caught = cols_[e].captured ? number(*cols_[e].captured) != 0.0
                                            : trace_.at(k - 1, int(e)).active && !trace_.at(k, int(e)).active;
      if (!caught) continue;
      int best = -1;
      double best_d = std::numeric_limits<double>::infinity();
      for (std::size_t p = 0; p < n; ++p) {
        if (trace_.roles[p] != game::Role::kPursuer) continue;
        const double d = (trace_.at(k, int(p)).state.position - trace_.at(k, int(e)).state.position).norm();
        if (d < best_d) best = int(p), best_d = d;
      }
      trace_.captures.push_back({k, t, best, int(e), best_d});
    }
  }

  const std::filesystem::path& file_;
  std::vector<std::string_view> header_;
  std::map<std::string, std::size_t, std::less<>> column_;
  std::vector<std::string> labels_;
  std::vector<AgentColumns> cols_;
  game::Trace trace_;
  std::vector<std::string_view> fields_;  // the row being read
  int line_ = 0;                          // its line number
};

}  // namespace

void write_trajectory_csv(const std::filesystem::path& file, const game::Trace& trace) {
  const int n = trace.agents;
  std::vector<std::string> labels;
  for (int i = 0; i < n; ++i) labels.push_back(game::agent_label(trace, i));
  std::vector<std::string> columns{"t"};
  for (const auto& l : labels)
    for (const char* c : {"_x", "_y", "_z"}) columns.push_back(l + c);
  for (const auto& l : labels)
    for (const char* c : {"_alpha", "_theta"}) columns.push_back(l + c);
  columns.emplace_back("distance");
  for (const auto& l : labels) {
    for (const char* c : {"d_target", "target_az", "target_el", "d_obstacle", "obstacle_az", "obstacle_el", "d_alpha",
                          "d_theta", "reward", "pinned"}) {
      columns.push_back(l + "_" + c);
    }
  }
  // Appended last, so the columns before keep their places: activity, the first collision of the step and,
  // for an evader, its capture in the step.
  for (const auto& l : labels) {
    columns.push_back(l + "_active");
    columns.push_back(l + "_hit");
    columns.push_back(l + "_captured");
  }
  AtomicFile out(file);
  CsvWriter csv(out.stream(), columns);
  for (int k = 0; k < trace.frame_count(); ++k) {
    auto row = csv.row();
    row.add(trace.times[std::size_t(k)]);
    for (int i = 0; i < n; ++i) {
      const Vec3& p = trace.at(k, i).state.position;
      row.add(p.x()).add(p.y()).add(p.z());
    }
    for (int i = 0; i < n; ++i) row.add(trace.at(k, i).state.heading.alpha).add(trace.at(k, i).state.heading.theta);
    // The smallest distance between a pursuer and an evader in the game.
    double distance = std::numeric_limits<double>::infinity();
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        if (trace.roles[std::size_t(i)] != game::Role::kPursuer || trace.roles[std::size_t(j)] != game::Role::kEvader ||
            !trace.at(k, j).active) {
          continue;
        }
        distance = std::min(distance, (trace.at(k, i).state.position - trace.at(k, j).state.position).norm());
      }
    }
    row.add(std::isfinite(distance) ? distance : std::numeric_limits<double>::quiet_NaN());
    for (int i = 0; i < n; ++i) {
      const game::AgentFrame& f = trace.at(k, i);
      const game::Percept& q = f.percept;
      row.add(q.target_distance)
          .add(q.target.azimuth)
          .add(q.target.elevation)
          .add(q.obstacle.distance)
          .add(q.to_obstacle.azimuth)
          .add(q.to_obstacle.elevation)
          .add(f.command.d_alpha)
          .add(f.command.d_theta)
          .add(f.reward)
          .add(static_cast<int>(q.pinned));
    }
    for (int i = 0; i < n; ++i) {
      const char* hit = "";
      for (const game::CollisionEvent& c : trace.collisions) {
        if (c.step == k && c.agent == i) {
          hit = world::to_string(c.kind);
          break;
        }
      }
      bool captured = false;
      for (const game::CaptureEvent& c : trace.captures) captured = captured || (c.step == k && c.evader == i);
      row.add(static_cast<int>(trace.at(k, i).active)).add(hit).add(static_cast<int>(captured));
    }
    row.end();
  }
  out.commit();
}

game::Trace read_trajectory_csv(const std::filesystem::path& file) {
  const std::string text = read_input_file(file, "trajectory file", kMaxTrajectoryFileBytes);
  const std::vector<std::string_view> lines = split_lines(text);
  if (lines.empty() || lines.front().empty()) throw InputError(file, 1, "", "no header line: not a trajectory file");
  TrajectoryReader reader(file, lines.front());
  for (std::size_t li = 1; li < lines.size(); ++li) {
    if (lines[li].empty() && li + 1 == lines.size()) break;  // the final newline
    reader.read_row(static_cast<int>(li + 1), lines[li]);
  }
  game::Trace trace = reader.take();
  if (trace.frame_count() == 0) throw InputError(file, 2, "", "no rows: the file holds no instant");
  return trace;
}

}  // namespace peg3d::results
