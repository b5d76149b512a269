#pragma once
// Replays: one recorded episode (a game::Trace) with its map, as the data the browser viewer draws
// (docs/viewer.md). The scene's fixed part (arena, obstacles, terrain simplified for drawing) is built once
// per map and shared by every episode written from it; the episode's part samples what the trace does not
// hold (movers' poses, the Apollonius sphere and the pursuer's cone of every pursuer-evader pair). What is
// recorded is never decimated: every frame of every agent goes into the file.

#include <cstddef>
#include <string>

#include <nlohmann/json.hpp>

#include "core/base64.hpp"

#include "game/episode.hpp"
#include "game/sim.hpp"
#include "world/arena.hpp"

namespace peg3d::view {

struct ReplaySettings {
  /// Terrain triangles drawn over all meshes, >= 1000; a larger terrain is simplified for drawing
  /// (meshoptimizer), its collision geometry untouched.
  std::size_t max_drawn_triangles = 200'000;
  /// Frames at which movers' poses and the pairs' geometry are sampled, >= 2: every frame up to this many,
  /// else this many evenly spread (the first and last included).
  int max_pose_samples = 20'000;
};

/// The drawn form of a triangle mesh: float positions and 32-bit indices, possibly simplified.
struct DrawnMesh {
  std::string name;
  std::size_t source_triangles = 0;
  std::vector<float> positions;  ///< x, y, z per vertex
  std::vector<std::uint32_t> indices;
  std::size_t triangle_count() const { return indices.size() / 3; }
};

/// `mesh` in float form, simplified to at most `max_triangles` when larger (never below what its topology
/// allows, then sloppily, so the bound holds). Unused vertices are dropped.
DrawnMesh drawn_mesh(const world::TriangleMesh& mesh, std::size_t max_triangles, std::string name);

/// The fixed part of every replay of one map.
class ReplayScene {
 public:
  /// Each mesh gets a share of the triangle budget in proportion to its size.
  ReplayScene(const world::Arena& arena, const ReplaySettings& settings = {});
  const nlohmann::json& json() const { return json_; }
  std::size_t drawn_triangles() const { return drawn_triangles_; }
  const ReplaySettings& settings() const { return settings_; }

 private:
  nlohmann::json json_;
  std::size_t drawn_triangles_ = 0;
  ReplaySettings settings_;
};

struct ReplayInfo {
  std::string title;     ///< what the episode is (scenario, policies)
  std::string subtitle;  ///< where it comes from and how it ended
};

/// The replay data of docs/viewer.md: `scene` (built from `sim`'s arena) plus every frame of `trace`, which
/// `sim` recorded (agent i of the trace is agent i of the sim's line-up: pursuers first).
nlohmann::json replay_json(const ReplayScene& scene, const game::Sim& sim, const game::Trace& trace,
                           const ReplayInfo& info);

}  // namespace peg3d::view
