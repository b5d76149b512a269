// peg3d._core: the C++ batch of games (env/batch.hpp) for the Python package around it (python/peg3d).
// Thin: it loads the map and configuration as the programs do, translates peg3d::InputError into
// peg3d.InputError (a ValueError), and shows the batch's buffers to numpy in place. Every argument the Python
// side passes is checked here too, so that no call sequence can reach the library with a bad value.

#include <Python.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "core/error.hpp"
#include "core/hash.hpp"
#include "core/validation.hpp"
#include "env/batch.hpp"
#include "experiment/facl_response.hpp"
#include "game/config_file.hpp"
#include "players/policy_io.hpp"
#include "players/registry.hpp"
#include "players/saved_policy.hpp"
#include "game/observation.hpp"
#include "game/scenario_choice.hpp"
#include "sense/scan_map.hpp"
#include "view/frame_renderer.hpp"
#include "view/replay.hpp"
#include "view/viewer_html.hpp"
#include "world/arena.hpp"
#include "world/map/map_loader.hpp"

namespace py = pybind11;
using namespace peg3d;

namespace {

std::unique_ptr<env::Batch> make_batch(const std::string& map, const std::string& config,
                                       const std::vector<std::string>& sets, bool cache, env::BatchSettings settings) {
  game::GameConfig c = game::apply_game_overrides(game::load_game_config(config), sets, players::check_players);
  const world::MapSpec spec = world::load_map(map);
  world::BuildOptions options;
  if (cache) options.cache_dir = world::default_cache_dir();
  return std::make_unique<env::Batch>(world::Arena::build(spec, options), std::move(c), std::move(settings));
}

// A read-only numpy view of the elements at `data`, shaped, kept alive by `owner` (the Batch's Python object).
// Without `strides`, the elements are contiguous in C order; strides are in bytes.
template <class T>
py::array numpy_view(py::handle owner, T* data, std::vector<py::ssize_t> shape, const char* dtype = nullptr,
                     std::vector<py::ssize_t> strides = {}) {
  if (strides.empty()) {
    strides.resize(shape.size());
    py::ssize_t s = sizeof(T);
    for (std::size_t k = shape.size(); k-- > 0;) strides[k] = s, s *= shape[k];
  }
  py::array a = dtype ? py::array(py::dtype(dtype), shape, strides, data, owner) : py::array(py::dtype::of<T>(), shape, strides, data, owner);
  a.attr("flags").attr("writeable") = false;
  return a;
}

// (low, high) as two float32 arrays.
py::tuple bounds_arrays(const env::ObservationBounds& o) {
  return py::make_tuple(py::array_t<float>(py::ssize_t(o.low.size()), o.low.data()),
                        py::array_t<float>(py::ssize_t(o.high.size()), o.high.data()));
}

game::Role role_named(const std::string& name) {
  if (name == "pursuer") return game::Role::kPursuer;
  if (name == "evader") return game::Role::kEvader;
  throw InvalidParameter("role", name, "must be pursuer or evader");
}

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "peg3d's C++ batch of games; use the peg3d package (parallel_env, vector_env) instead";
  py::register_exception<InputError>(m, "InputError", PyExc_ValueError);
  // A batch over its memory budget: a MemoryError (registered after InputError, so tried before it).
  py::register_exception<env::MemoryBudgetError>(m, "MemoryBudgetError", PyExc_MemoryError);

  // The configuration presets, from the one list the library keeps (game::kPresetNames).
  py::tuple presets(std::size(game::kPresetNames));
  for (std::size_t i = 0; i < std::size(game::kPresetNames); ++i) presets[i] = game::kPresetNames[i];
  m.attr("PRESETS") = presets;
  // The observation's first entries as the library declares them (game::kObservationEntries): (name, unit,
  // meaning) each.
  py::tuple entries(game::kObservationEntries.size());
  for (std::size_t i = 0; i < game::kObservationEntries.size(); ++i) {
    const game::ObservationEntry& e = game::kObservationEntries[i];
    entries[i] = py::make_tuple(e.name, e.unit, e.meaning);
  }
  m.attr("OBSERVATION_ENTRIES") = entries;

  // The players' registry (players/registry.hpp), the one list of players: (name, roles, needs, help) each, and
  // each role's baselines (the default line-ups).
  py::list players;
  for (const players::PlayerInfo& p : players::registry()) {
    py::list roles;
    for (const game::Role r : {game::Role::kPursuer, game::Role::kEvader}) {
      if (p.plays(r)) roles.append(game::to_string(r));
    }
    py::list needs;
    if (p.learns()) needs.append("training");
    if ((p.needs & players::kNeedsSight) != 0) needs.append("sight");
    players.append(py::make_tuple(std::string(p.name), py::tuple(roles), py::tuple(needs), std::string(p.help)));
  }
  m.attr("PLAYERS") = py::tuple(players);
  py::dict baselines;
  for (const game::Role r : {game::Role::kPursuer, game::Role::kEvader}) {
    baselines[game::to_string(r)] = py::tuple(py::cast(players::baseline_players(r)));
  }
  m.attr("BASELINE_PLAYERS") = baselines;

  py::class_<env::Batch> batch(m, "Batch");
  batch.def(py::init([](const std::string& map, const std::string& config, const std::vector<std::string>& sets,
                       const std::vector<std::string>& scenarios, int games, int threads, std::uint64_t seed, int neighbours,
                       const std::vector<std::pair<std::string, std::vector<std::pair<std::string, double>>>>& controllers,
                       bool cache, bool record, std::size_t memory_budget) {
             env::BatchSettings s;
             s.games = games, s.threads = threads, s.seed = seed, s.neighbours = neighbours;
             s.scenarios = scenarios;
             // (agent or role, [(policy, weight), ...]): BatchSettings::controllers' mixtures.
             for (const auto& [key, members] : controllers) {
               auto& mixture = s.controllers.emplace_back(key, std::vector<env::MixtureEntry>{}).second;
               for (const auto& [policy, weight] : members) mixture.push_back({policy, weight});
             }
             s.record = record;
             s.memory_budget = memory_budget;
             py::gil_scoped_release unlocked;  // building a world can take seconds
             return make_batch(map, config, sets, cache, std::move(s));
           }),
           py::arg("map"), py::arg("config"), py::arg("sets"), py::arg("scenarios"), py::arg("games"),
           py::arg("threads"), py::arg("seed"), py::arg("neighbours"), py::arg("controllers"), py::arg("cache") = true,
           py::arg("record") = false, py::arg("memory_budget") = 0)
      .def_property_readonly("games", &env::Batch::games)
      .def_property_readonly("agents", &env::Batch::agents)
      .def_property_readonly("pursuers", &env::Batch::pursuers)
      .def_property_readonly("observation_size", &env::Batch::observation_size)
      .def_property_readonly("agent_names", &env::Batch::agent_names)
      .def_property_readonly("global_state_size", &env::Batch::global_state_size)
      .def_property_readonly("dt", [](const env::Batch& b) { return b.sim().config().dt; })
      .def_property_readonly("max_steps", [](const env::Batch& b) { return b.sim().max_steps(); })
      .def_property_readonly("map_name", [](const env::Batch& b) { return b.sim().arena().map().name; })
      .def_property_readonly("scenario_names", &env::Batch::scenario_names)
      .def("controlled", [](const env::Batch& b, int i) {
        if (i < 0 || i >= b.agents()) throw py::index_error("no such agent");
        return b.controlled(i);
      })
      .def("mixture", [](const env::Batch& b, int i) {
        // Agent i's C++ players as given: [(policy, weight), ...]; empty for the caller's agents.
        if (i < 0 || i >= b.agents()) throw py::index_error("no such agent");
        py::list out;
        for (const env::MixtureEntry& e : b.mixture(i)) out.append(py::make_tuple(e.policy, e.weight));
        return out;
      })
      .def("members", [](const env::Batch& b) {
        // games x agents: the member of its mixture each agent plays this episode (-1: the caller's agents).
        py::array_t<std::int32_t> out({b.games(), b.agents()});
        auto m = out.mutable_unchecked<2>();
        for (int g = 0; g < b.games(); ++g) {
          for (int i = 0; i < b.agents(); ++i) m(g, i) = b.member(g, i);
        }
        return out;
      })
      .def("observation_bounds", [](const env::Batch& b, int i) {
        if (i < 0 || i >= b.agents()) throw py::index_error("no such agent");
        return bounds_arrays(b.observation_bounds(i));
      })
      .def("observation_segments", [](const env::Batch& b, int i) {
        // Agent i's observation as the library lays it out (game::observation_table): one dict per segment.
        if (i < 0 || i >= b.agents()) throw py::index_error("no such agent");
        py::list out;
        for (const sense::Segment& s : b.observation_table(i).segments) {
          py::dict d;
          d["name"] = s.name;
          d["offset"] = s.offset;
          d["size"] = s.size;
          d["unit"] = s.unit;
          d["low"] = py::array_t<float>(py::ssize_t(s.low.size()), s.low.data());
          d["high"] = py::array_t<float>(py::ssize_t(s.high.size()), s.high.data());
          d["meaning"] = s.meaning;
          d["shape"] = py::tuple(py::cast(s.shape));
          out.append(d);
        }
        return out;
      })
      .def("state_bounds", [](const env::Batch& b) { return bounds_arrays(b.state_bounds()); })
      .def("action_bound", [](const env::Batch& b, bool pursuer) {
        return b.action_bound(pursuer ? game::Role::kPursuer : game::Role::kEvader);
      })
      .def("reset", [](env::Batch& b, std::optional<std::uint64_t> seed) {
        py::gil_scoped_release unlocked;
        b.reset(seed);
      }, py::arg("seed") = py::none())
      .def("reset_game", [](env::Batch& b, int g, std::optional<std::uint64_t> seed) {
        if (g < 0 || g >= b.games()) throw py::index_error("no such game");
        b.reset_game(g, seed);
      }, py::arg("game"), py::arg("seed") = py::none())
      .def("step", [](env::Batch& b, py::array_t<double, py::array::c_style | py::array::forcecast> a) {
        if (a.ndim() != 3 || a.shape(0) != b.games() || a.shape(1) != b.agents() || a.shape(2) != 2) {
          throw py::value_error("actions must have the shape (games, agents, 2)");
        }
        {
          py::gil_scoped_release unlocked;
          b.step(a.data());
        }
        // Ctrl-C during the step: the signal handler ran while the GIL was released; raise it now.
        if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      })
      .def_property_readonly("observations", [](py::object self) {
        env::Batch& b = self.cast<env::Batch&>();
        return numpy_view(self, b.observations(), {b.games(), b.agents(), b.observation_size()});
      })
      .def("segment_view", [](py::object self, int offset, std::vector<py::ssize_t> shape, int first, int count) {
        // Agents first .. first + count - 1's entries [offset, offset + prod(shape)) of every game's observations,
        // shaped (games, count, *shape): the same memory, read-only. The caller gives a segment's offset and shape
        // from observation_segments (the agents must share them).
        env::Batch& b = self.cast<env::Batch&>();
        py::ssize_t size = 1;
        for (const py::ssize_t d : shape) {
          if (d < 1) throw py::value_error("a segment's shape has positive dimensions");
          size *= d;
        }
        if (first < 0 || count < 1 || first + count > b.agents()) throw py::index_error("no such agents");
        if (offset < 0 || offset + size > b.observation_size()) throw py::index_error("not within an observation");
        const py::ssize_t f = sizeof(float), stride = b.observation_size();
        std::vector<py::ssize_t> dims{b.games(), count}, strides{stride * b.agents() * f, stride * f};
        std::vector<py::ssize_t> inner(shape.size());
        py::ssize_t step = f;
        for (std::size_t k = shape.size(); k-- > 0;) inner[k] = step, step *= shape[k];
        dims.insert(dims.end(), shape.begin(), shape.end());
        strides.insert(strides.end(), inner.begin(), inner.end());
        return numpy_view(self, b.observations() + std::size_t(first) * std::size_t(stride) + std::size_t(offset), dims, nullptr,
                          strides);
      }, py::arg("offset"), py::arg("shape"), py::arg("first"), py::arg("count"))
      .def_property_readonly("rewards", [](py::object self) {
        env::Batch& b = self.cast<env::Batch&>();
        return numpy_view(self, b.rewards(), {b.games(), b.agents()});
      })
      .def_property_readonly("reward_terms", [](py::object self) {
        env::Batch& b = self.cast<env::Batch&>();
        return numpy_view(self, b.reward_terms(), {b.games(), b.agents(), 3});
      })
      .def_property_readonly("reset_flags", [](py::object self) {
        env::Batch& b = self.cast<env::Batch&>();
        return numpy_view(self, b.reset_flags(), {b.games()}, "bool");
      })
      .def("global_state", [](const env::Batch& b, int g) {
        if (g < 0 || g >= b.games()) throw py::index_error("no such game");
        const std::vector<float> s = b.global_state(g);
        return py::array_t<float>(py::ssize_t(s.size()), s.data());
      })
      .def("global_states", [](const env::Batch& b) {
        // Every game's global_state, one row each (games x global_state_size), a copy.
        py::array_t<float> out({b.games(), b.global_state_size()});
        float* row = out.mutable_data();
        for (int g = 0; g < b.games(); ++g, row += b.global_state_size()) {
          const std::vector<float> s = b.global_state(g);
          std::copy(s.begin(), s.end(), row);
        }
        return out;
      })
      .def("agent_commands", [](const env::Batch& b, int g) {
        // Every agent's steering command of game g's last step (rad, d_alpha and d_theta), whoever gave it: the
        // caller's actions as stepped, or what a C++ player chose; zeros before the first step of an episode.
        if (g < 0 || g >= b.games()) throw py::index_error("no such game");
        const game::SimState& st = b.state(g);
        py::array_t<double> out({py::ssize_t(st.agent_count()), py::ssize_t(2)});
        auto o = out.mutable_unchecked<2>();
        for (int i = 0; i < st.agent_count(); ++i) {
          const Steering u = st.step > 0 ? st.events.agents[std::size_t(i)].command : Steering{};
          o(i, 0) = u.d_alpha, o(i, 1) = u.d_theta;
        }
        return out;
      })
      .def("agent_states", [](const env::Batch& b, int g) {
        // Every agent's x, y, z, alpha, theta in double precision (what trajectory hashes cover), a copy.
        if (g < 0 || g >= b.games()) throw py::index_error("no such game");
        const game::SimState& st = b.state(g);
        py::array_t<double> out({py::ssize_t(st.agent_count()), py::ssize_t(5)});
        auto o = out.mutable_unchecked<2>();
        for (int i = 0; i < st.agent_count(); ++i) {
          const KinematicState& k = st.agents[std::size_t(i)].kinematics;
          o(i, 0) = k.position.x(), o(i, 1) = k.position.y(), o(i, 2) = k.position.z();
          o(i, 3) = k.heading.alpha, o(i, 4) = k.heading.theta;
        }
        return out;
      })
      .def("write_map", [](const env::Batch& b, int g, int i, const std::string& file) {
        // Agent i's own map in game g as it is now, as OctoMap's .bt file (docs/sensing.md).
        if (g < 0 || g >= b.games()) throw py::index_error("no such game");
        if (i < 0 || i >= b.agents()) throw py::index_error("no such agent");
        const sense::ScanMap* map = b.state(g).map(i);
        if (map == nullptr) throw py::value_error(b.agent_names()[std::size_t(i)] + " has no map (map.enabled)");
        py::gil_scoped_release unlocked;
        map->write_bt(file);
      })
      .def("episode", [](const env::Batch& b, int g) {
        if (g < 0 || g >= b.games()) throw py::index_error("no such game");
        return b.episode(g);
      })
      .def("write_replay", [](const env::Batch& b, const std::string& file, const std::string& assets,
                              const std::string& title, const std::string& subtitle) {
        // The browser replay (docs/viewer.md) of game 0's episode so far, as peg-matchup --html writes one.
        const game::Trace* trace = b.trace(0);
        if (trace == nullptr) throw py::value_error("render: the environment was made without render_mode=\"html\"");
        const view::ViewerAssets viewer = view::ViewerAssets::load(assets);
        py::gil_scoped_release unlocked;  // simplifying terrain for drawing can take a while
        const view::ReplayScene scene(b.sim().arena());
        view::write_viewer_html(file, viewer, view::replay_json(scene, b.sim(), *trace, {title, subtitle}), title);
      })
      .def("game_info", [](const env::Batch& b, int g) {
        if (g < 0 || g >= b.games()) throw py::index_error("no such game");
        const game::SimState& st = b.state(g);
        py::dict d;
        d["step"] = st.step;
        d["time"] = st.time;
        d["done"] = st.done;
        d["outcome"] = st.done ? std::string(game::to_string(st.outcome)) : std::string();
        d["collisions"] = st.collisions;
        d["free_evaders"] = st.free_evaders;
        return d;
      });
  // The per-agent flags, games x agents, as bool views.
  using Flags = std::uint8_t* (env::Batch::*)();
  for (const auto& [name, flags] : {std::pair<const char*, Flags>{"terminated", &env::Batch::terminated},
                                    {"truncated", &env::Batch::truncated}, {"acted", &env::Batch::acted},
                                    {"active", &env::Batch::active}, {"collided", &env::Batch::collided},
                                    {"captured", &env::Batch::captured}}) {
    batch.def_property_readonly(name, [flags = flags](py::object self) {
      env::Batch& b = self.cast<env::Batch&>();
      return numpy_view(self, (b.*flags)(), {b.games(), b.agents()}, "bool");
    });
  }

  // A policy file of any kind (FACL, MLP, peg3d-mixture) read as the C++ programs read it for an agent of `role`:
  // peg3d.read_policy's check, so that Python and C++ accept and refuse the same files with the same messages.
  m.def(
      "check_policy",
      [](const std::string& file, const std::string& role_name) {
        const game::Role role = role_named(role_name);
        (void)players::load_saved_policy(file, role);
      },
      py::arg("file"), py::arg("role"));

  // A FACL best response (experiment/facl_response.hpp) against `opponent`, a policy file of the other role (a
  // classic player goes in a one-member peg3d-mixture file), saved to `out` as a FACL policy file.
  m.def(
      "train_facl",
      [](const std::string& map, const std::string& config, const std::vector<std::string>& sets,
         const std::vector<std::string>& scenarios, const std::string& role_name, const std::string& opponent,
         int episodes, std::uint64_t seed, const std::string& out, bool cache) {
        const game::Role role = role_named(role_name);
        py::gil_scoped_release unlocked;  // building the world and training take seconds to hours
        game::GameConfig c = game::apply_game_overrides(game::load_game_config(config), sets, players::check_players);
        const game::Role other = role == game::Role::kPursuer ? game::Role::kEvader : game::Role::kPursuer;
        const auto saved = players::load_saved_policy(opponent, other);
        world::BuildOptions options;
        if (cache) options.cache_dir = world::default_cache_dir();
        auto arena = world::Arena::build(world::load_map(map), options);
        c = experiment::with_opponent_config(std::move(c), other, game::most_agents(arena->map(), other), *saved);
        const auto sim = std::make_shared<const game::Sim>(std::move(arena), std::move(c));
        saved->check_fits(*sim, other);
        experiment::FaclResponseSettings s;
        s.episodes = episodes, s.scenarios = scenarios, s.seed = seed;
        const players::RoleModels models = experiment::train_facl_response(*sim, role, *saved, s);
        // A team of equal settings learns one model; one file holds one.
        if (models.models.size() != 1) {
          throw InvalidParameter(role_name + ".policy", "facl", "a team whose agents' settings differ learns several models");
        }
        players::save_policy(out, *models.models.front());
      },
      py::arg("map"), py::arg("config"), py::arg("sets"), py::arg("scenarios"), py::arg("role"), py::arg("opponent"),
      py::arg("episodes"), py::arg("seed"), py::arg("out"), py::arg("cache") = true);

  // Images of a batch's games (render_mode "rgb_array"): the camera and the map's fixed solids are drawn once.
  py::class_<view::FrameRenderer>(m, "FrameRenderer")
      .def(py::init([](const env::Batch& b, int width, int height) {
             view::FrameSettings s;
             s.width = width;
             s.height = height;
             return std::make_unique<view::FrameRenderer>(b.sim(), s);
           }),
           py::arg("batch"), py::arg("width") = 640, py::arg("height") = 480, py::keep_alive<1, 2>())
      .def("render", [](view::FrameRenderer& f, const env::Batch& b, int g) {
        if (g < 0 || g >= b.games()) throw py::index_error("no such game");
        py::array_t<std::uint8_t> image({f.height(), f.width(), 3});
        std::span<std::uint8_t> out(image.mutable_data(), std::size_t(image.size()));
        {
          py::gil_scoped_release unlocked;
          f.render(b.state(g), out);
        }
        return image;
      });
}
