#include "regress/collision_case.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "core/error.hpp"
#include "core/input_files.hpp"
#include "core/random.hpp"
#include "core/yaml_input.hpp"
#include "game/config_file.hpp"
#include "players/lineup.hpp"
#include "players/registry.hpp"
#include "players/saved_policy.hpp"
#include "geometry/angles.hpp"
#include "world/map/map_loader.hpp"
#include "world/map/map_spec.hpp"

namespace peg3d::regress {
namespace {

int line_of(const YAML::Node& n) { return n.IsDefined() && n.Mark().line >= 0 ? n.Mark().line + 1 : 0; }

[[noreturn]] void fail(const std::filesystem::path& file, const YAML::Node& at, const std::string& field,
                       const std::string& message) {
  throw InputError(file, line_of(at), field, message);
}

std::string scalar(const std::filesystem::path& file, const YAML::Node& n, const std::string& field) {
  if (!n.IsScalar() || n.Scalar().empty()) fail(file, n, field, "expects a word or a path");
  return n.Scalar();
}

double number(const std::filesystem::path& file, const YAML::Node& n, const std::string& field) {
  double v = 0.0;
  if (!n.IsScalar() || !YAML::convert<double>::decode(n, v) || !std::isfinite(v)) {
    fail(file, n, field, "expects a finite number");
  }
  return v;
}

// The numbers of one line of a motion file (comments removed); empty for a blank line.
std::vector<double> numbers_of(const std::filesystem::path& file, int line, std::string text) {
  if (const auto hash = text.find('#'); hash != std::string::npos) text.erase(hash);
  std::stringstream in(text);
  std::vector<double> out;
  std::string word;
  while (in >> word) {
    char* end = nullptr;
    const double v = std::strtod(word.c_str(), &end);
    if (end == word.c_str() || *end != '\0' || !std::isfinite(v)) {
      throw InputError(file, line, "", fmt::format("'{}' is not a finite number", shown(word)));
    }
    out.push_back(v);
  }
  return out;
}

std::vector<std::vector<double>> rows_of(const std::filesystem::path& file) {
  std::stringstream in(read_input_file(file, "motion file"));
  std::vector<std::vector<double>> rows;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    auto row = numbers_of(file, n, line);
    if (!row.empty()) {
      row.push_back(n);  // the line, for messages
      rows.push_back(std::move(row));
    }
  }
  return rows;
}

std::vector<game::TimedCommand> commands_of(const std::filesystem::path& file,
                                            const std::vector<std::vector<double>>& rows) {
  std::vector<game::TimedCommand> out;
  for (const auto& r : rows) {
    const int line = static_cast<int>(r.back());
    if (r.size() != 4) throw InputError(file, line, "", "expects 3 numbers: time_s d_alpha_deg d_theta_deg");
    if (r[0] < 0.0) throw InputError(file, line, "", "the time must be >= 0");
    if (!out.empty() && r[0] < out.back().time) throw InputError(file, line, "", "times must not decrease");
    out.push_back({r[0], {r[1] * kPi / 180.0, r[2] * kPi / 180.0}});
  }
  return out;
}

std::vector<game::Waypoint> waypoints_of(const std::filesystem::path& file, const std::vector<std::vector<double>>& rows) {
  std::vector<game::Waypoint> out;
  for (const auto& r : rows) {
    const int line = static_cast<int>(r.back());
    if (r.size() != 4 && r.size() != 5) throw InputError(file, line, "", "expects x y z, or x y z time_s");
    out.push_back({Vec3(r[0], r[1], r[2]), r.size() == 5 ? r[3] : -1.0});
  }
  return out;
}

// The rows of an inline motion: a YAML list of lists of numbers.
std::vector<std::vector<double>> inline_rows(const std::filesystem::path& file, const YAML::Node& n,
                                             const std::string& field) {
  std::vector<std::vector<double>> rows;
  for (std::size_t i = 0; i < n.size(); ++i) {
    if (!n[i].IsSequence()) fail(file, n[i], fmt::format("{}[{}]", field, i), "expects a list of numbers");
    std::vector<double> row;
    for (std::size_t k = 0; k < n[i].size(); ++k) row.push_back(number(file, n[i][k], fmt::format("{}[{}][{}]", field, i, k)));
    row.push_back(line_of(n[i]));
    rows.push_back(std::move(row));
  }
  return rows;
}

}  // namespace

std::vector<game::TimedCommand> read_commands(const std::filesystem::path& file) { return commands_of(file, rows_of(file)); }
std::vector<game::Waypoint> read_waypoints(const std::filesystem::path& file) { return waypoints_of(file, rows_of(file)); }

std::string scenario_label(const world::Scenario& s, int i) {
  const int p = static_cast<int>(s.pursuers.size());
  return game::agent_label(game::role_at(i, p), game::rank_at(i, p));
}

CollisionCase load_case(const std::filesystem::path& path) {
  CollisionCase c;
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    c.file = path / "case.yaml";
    c.golden = path / "golden.log";
    c.name = std::filesystem::absolute(path).lexically_normal().filename().string();
    if (c.name.empty()) c.name = std::filesystem::absolute(path).lexically_normal().parent_path().filename().string();
  } else {
    c.file = path;
    c.golden = std::filesystem::path(path).replace_extension(".log");
    c.name = path.stem().string();
  }
  const std::filesystem::path dir = std::filesystem::absolute(c.file).parent_path();
  const YAML::Node root = parse_yaml_text(read_input_file(c.file, "case file (a folder with case.yaml, or a .yaml file)"), c.file);
  if (!root.IsMap()) throw InputError(c.file, 1, "", "expects a mapping (map: ..., agents: ...)");
  for (const auto& kv : root) {
    const std::string key = kv.first.Scalar();
    if (key != "map" && key != "scenario" && key != "config" && key != "set" && key != "seed" && key != "agents") {
      fail(c.file, kv.first, shown(key), "unknown key (allowed: map, scenario, config, set, seed, agents)");
    }
  }
  if (!root["map"]) throw InputError(c.file, 1, "map", "missing required field");
  c.map = (dir / scalar(c.file, root["map"], "map")).lexically_normal();
  if (root["scenario"]) {
    c.scenario = scalar(c.file, root["scenario"], "scenario");
    c.scenario_line = line_of(root["scenario"]);
  }
  if (root["config"]) {
    c.config = scalar(c.file, root["config"], "config");
    if (std::filesystem::path(c.config).extension() == ".json") c.config = (dir / c.config).lexically_normal().string();
  }
  if (const YAML::Node set = root["set"]) {
    if (!set.IsSequence()) fail(c.file, set, "set", "expects a list of key=value");
    for (std::size_t i = 0; i < set.size(); ++i) c.overrides.push_back(scalar(c.file, set[i], fmt::format("set[{}]", i)));
  }
  if (const YAML::Node seed = root["seed"]) {
    unsigned long long v = 0;
    if (!seed.IsScalar() || !YAML::convert<unsigned long long>::decode(seed, v)) fail(c.file, seed, "seed", "expects a non-negative integer");
    c.seed = v;
  }
  if (const YAML::Node agents = root["agents"]) {
    if (!agents.IsMap()) fail(c.file, agents, "agents", "expects a mapping of agent labels");
    for (const auto& kv : agents) {
      AgentDriver d;
      d.label = kv.first.Scalar();
      d.line = line_of(kv.first);
      const std::string field = "agents." + d.label;
      const YAML::Node& spec = kv.second;
      if (!spec.IsMap() || spec.size() != 1) fail(c.file, spec, field, "expects one of commands, waypoints, policy, scripted");
      const std::string how = spec.begin()->first.Scalar();
      const YAML::Node value = spec.begin()->second;
      const auto rows = [&]() {
        if (value.IsSequence()) return inline_rows(c.file, value, field + "." + how);
        return rows_of(dir / scalar(c.file, value, field + "." + how));
      };
      const std::filesystem::path source = value.IsSequence() ? c.file : dir / (value.IsScalar() ? value.Scalar() : "");
      if (how == "commands") {
        d.kind = AgentDriver::Kind::kCommands;
        d.commands = commands_of(source, rows());
      } else if (how == "waypoints") {
        d.kind = AgentDriver::Kind::kWaypoints;
        d.waypoints = waypoints_of(source, rows());
      } else if (how == "policy") {
        d.kind = AgentDriver::Kind::kPolicy;
        d.policy = dir / scalar(c.file, value, field + ".policy");
      } else if (how == "scripted") {
        d.kind = AgentDriver::Kind::kScripted;
        const std::string name = scalar(c.file, value, field + ".scripted");
        const players::PlayerInfo* player = players::find_player(name);
        if (player == nullptr || player->learns()) fail(c.file, value, field + ".scripted", "'" + shown(name) + "' is not a scripted policy");
        d.scripted = std::string(player->name);
      } else {
        fail(c.file, spec.begin()->first, field + "." + how, "unknown driver (allowed: commands, waypoints, policy, scripted)");
      }
      c.drivers.push_back(std::move(d));
    }
  }
  return c;
}

std::vector<std::filesystem::path> find_cases(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_directory(path, ec) || std::filesystem::exists(path / "case.yaml", ec)) return {path};
  std::vector<std::filesystem::path> out;
  for (const auto& entry : std::filesystem::directory_iterator(path, ec)) {
    if (entry.is_directory() && std::filesystem::exists(entry.path() / "case.yaml")) out.push_back(entry.path());
    if (entry.is_regular_file() && entry.path().extension() == ".yaml") out.push_back(entry.path());
  }
  std::sort(out.begin(), out.end());
  if (out.empty()) throw InputError(path, 0, "", "holds no case (folders with case.yaml, or .yaml files)");
  return out;
}

CasePlay play_case(const CollisionCase& c, bool use_cache) {
  world::BuildOptions options;
  if (use_cache) options.cache_dir = world::default_cache_dir();
  const auto arena = world::Arena::build(world::load_map(c.map), options);
  game::GameConfig config =
      game::apply_game_overrides(game::load_game_config(c.config, players::check_players), c.overrides, players::check_players);
  const auto& scenarios = arena->map().scenarios;
  const world::Scenario* scenario = c.scenario.empty() ? &scenarios.front() : arena->map().find_scenario(c.scenario);
  if (scenario == nullptr) throw InputError(c.file, c.scenario_line, "scenario", "'" + shown(c.scenario) + "' is not a scenario of " + c.map.string());

  // Every driver names an agent of the scenario.
  const int n = scenario->agents(), p = static_cast<int>(scenario->pursuers.size());
  std::vector<const AgentDriver*> driver_of(std::size_t(n), nullptr);
  for (const AgentDriver& d : c.drivers) {
    bool found = false;
    // Cases written before issue 37 name agents as logs then did (game::current_agent_label reads those labels);
    // the role alone named only the only agent of its role, so in a team it names none.
    const std::string label = game::current_agent_label(d.label);
    const bool bare_role = d.label == to_string(game::Role::kPursuer) || d.label == to_string(game::Role::kEvader);
    for (int i = 0; i < n; ++i) {
      const bool alone = (game::role_at(i, p) == game::Role::kPursuer ? p : n - p) == 1;
      if (label == scenario_label(*scenario, i) && (alone || !bare_role)) {
        driver_of[std::size_t(i)] = &d;
        found = true;
      }
    }
    if (!found) throw InputError(c.file, d.line, "agents." + d.label, "no agent of scenario '" + scenario->name + "' has this label");
  }
  // A saved FACL policy plays with the agent configuration it was saved with (its guard, steering, observation),
  // as in peg-matchup: its agent's entry in the game configuration becomes that one. An MLP plays with the
  // case's configuration.
  std::vector<std::shared_ptr<const players::SavedPolicy>> saved(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const AgentDriver* d = driver_of[std::size_t(i)];
    if (d == nullptr || d->kind != AgentDriver::Kind::kPolicy) continue;
    const game::Role role = game::role_at(i, p);
    saved[std::size_t(i)] = players::load_saved_policy(d->policy, role);
    if (const game::AgentConfig* own = saved[std::size_t(i)]->config()) config.set_agent(role, game::rank_at(i, p), *own);
  }
  const game::Sim sim(arena, config);
  for (int i = 0; i < n; ++i) {
    if (saved[std::size_t(i)]) saved[std::size_t(i)]->check_fits(sim, game::role_at(i, p), game::rank_at(i, p));
  }
  players::Lineup lineup;
  for (int i = 0; i < n; ++i) {
    const game::Role role = game::role_at(i, p);
    const int rank = game::rank_at(i, p);
    const std::uint64_t team_seed = derive_seed(c.seed, {role == game::Role::kPursuer ? 1u : 2u});
    const std::uint64_t seed = players::agent_seed(team_seed, rank);
    const AgentDriver* d = driver_of[std::size_t(i)];
    if (d == nullptr) {
      lineup.add(players::make_player(config.agent(role, rank), role, seed));
    } else if (d->kind == AgentDriver::Kind::kCommands) {
      lineup.add(std::make_unique<game::TimedCommands>(d->commands));
    } else if (d->kind == AgentDriver::Kind::kWaypoints) {
      lineup.add(std::make_unique<game::WaypointFollower>(d->waypoints));
    } else if (d->kind == AgentDriver::Kind::kPolicy) {
      lineup.add(saved[std::size_t(i)]->make(seed, config.agent(role, rank), role, team_seed));
    } else {
      game::AgentConfig a = config.agent(role, rank);
      a.policy = d->scripted;
      if (!players::find_player(a.policy)->plays(role)) {
        throw InputError(c.file, d->line, "agents." + d->label + ".scripted",
                         fmt::format("{} does not play the {}", a.policy, game::to_string(role)));
      }
      lineup.add(players::make_player(a, role, seed));
    }
  }
  game::SimState state(sim);
  game::Trace trace;
  trace.reserve(sim.max_steps(), n);
  game::play(sim, state, *scenario, lineup.policies(), /*learning=*/false, c.seed, &trace);
  CollisionLog log = make_log(c.name, trace, state, sim.movers());
  return {sim, std::move(trace), std::move(log)};
}

CollisionLog run_case(const CollisionCase& c, bool use_cache) { return play_case(c, use_cache).log; }

}  // namespace peg3d::regress
