#pragma once
// A named part of an agent's observation vector (issue 50), in the manner of MuJoCo's sensor_adr and sensor_dim:
// where it starts, how many float entries it holds, their unit and bounds, and what they mean. An agent's
// observation is a list of segments (game/observation.hpp builds it once from the game's settings: the base
// entries, the neighbour slots, and every segment its sensors add); the Python front, the policy files and the
// viewer read that list instead of computing offsets.

#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace peg3d::sense {

struct Segment {
  std::string name;     ///< unique within an observation: "target_distance", "neighbour.teammate.0.offset", "lidar.ranges"
  int offset = 0;       ///< its first entry's index in the observation
  int size = 0;         ///< entries, >= 1
  std::string unit;     ///< "m", "rad", "m/s", "s", or "" for a number without one (a mask, a flag)
  std::vector<float> low, high;  ///< per entry: the bounds every value lies within (size long each)
  std::string meaning;  ///< one line, as the viewer and the docs say it
  /// How its entries are laid out, row-major: {size} for a list, {rows, columns} for an image (a depth camera's).
  std::vector<int> shape;

  /// A segment of `size` entries, each within [low, high], laid out as `shape` ({size} when empty).
  static Segment uniform(std::string name, int size, std::string unit, double low, double high, std::string meaning,
                         std::vector<int> shape = {});
};

/// The segments' total size (the last one's end; they tile the observation in order).
int observation_size(std::span<const Segment> segments);

/// Sets every segment's offset so that they follow each other from 0, in order.
void lay_out(std::span<Segment> segments);

/// A segment list as a policy file records it: [{"name", "size", "unit"}, ...] (bounds and meanings depend on the
/// arena, not on what a network reads).
nlohmann::json segments_to_json(std::span<const Segment> segments);

/// The segments a policy file records (name, size and unit each; offsets laid out in order). Throws
/// std::invalid_argument with a message naming the entry ("observation[3].size") on one that does not fit: not a
/// list, a name that is empty or longer than 80 characters, a size outside [1, 2^20], a unit longer than 8, more
/// than 4096 segments.
std::vector<Segment> segments_from_json(const nlohmann::json& j);

/// The first segment where `a` and `b` differ in name, size or unit, as text ("segment 20: lidar.ranges (16 m)
/// where the game has neighbour.opponent.0.offset (3 m)"); nullopt when they agree segment for segment.
std::optional<std::string> first_difference(std::span<const Segment> a, std::span<const Segment> b);

}  // namespace peg3d::sense
