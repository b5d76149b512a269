#pragma once
// Images of a game as it stands, for learners' videos (the Python front's render_mode "rgb_array"): a software
// z-buffer rasteriser, no display and no GPU. A fixed camera looks at the arena from above one corner; the
// map's fixed solids (floor, terrain, spheres, cylinders) are drawn once into a base image with its depth,
// and each frame copies it and draws what moves (movers, pushed bodies, agents) into the copy, flat-shaded.

#include <cstdint>
#include <span>
#include <vector>

#include "game/sim.hpp"
#include "geometry/vector.hpp"

namespace peg3d::view {

struct FrameSettings {
  int width = 640;                ///< pixels, [16, 4096]
  int height = 480;               ///< pixels, [16, 4096]
  double vertical_fov = 50.0;     ///< deg, (10, 120)
  /// m: agents are drawn as balls of their collision radius, but at least this large so that they show.
  double min_agent_radius = 0.4;
};

/// The colours, as 0-255 RGB, so that tests and users can tell what a pixel shows.
struct FramePalette {
  static constexpr std::uint8_t kPursuer[3] = {220, 40, 30};
  static constexpr std::uint8_t kEvader[3] = {30, 90, 235};
  static constexpr std::uint8_t kInactive[3] = {150, 150, 150};
  static constexpr std::uint8_t kObstacle[3] = {150, 130, 110};
  static constexpr std::uint8_t kTerrain[3] = {125, 140, 110};
  static constexpr std::uint8_t kMover[3] = {235, 160, 50};
  static constexpr std::uint8_t kBody[3] = {160, 120, 210};
};

class FrameRenderer {
 public:
  /// Builds the camera and the base image of `sim`'s arena, which must outlive the renderer.
  explicit FrameRenderer(const game::Sim& sim, const FrameSettings& settings = {});

  int width() const { return settings_.width; }
  int height() const { return settings_.height; }
  /// Writes `state`'s image into `rgb`: height rows of width pixels, top row first, 3 bytes a pixel.
  void render(const game::SimState& state, std::span<std::uint8_t> rgb);
  /// Where the camera sees p: pixel column and row (fractions; the pixel's centre is at + 0.5) and depth (m,
  /// along the view axis; <= 0 behind the camera).
  Vec3 project(const Vec3& p) const;
  const Vec3& eye() const { return eye_; }

 private:
  struct Triangle {
    Vec3 a, b, c;
    std::uint8_t colour[3];
  };
  void draw(const Triangle& t, std::vector<std::uint8_t>& rgb, std::vector<float>& depth) const;

  const game::Sim& sim_;
  FrameSettings settings_;
  Vec3 eye_, right_, up_, forward_;
  double focal_ = 1.0;  // pixels per unit of tan(angle)
  std::vector<std::uint8_t> base_rgb_, rgb_;
  std::vector<float> base_depth_, depth_;
  std::vector<Triangle> scratch_;  // what moves, rebuilt each frame
};

}  // namespace peg3d::view
