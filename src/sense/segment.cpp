#include "sense/segment.hpp"

#include <stdexcept>

#include <fmt/format.h>

namespace peg3d::sense {
namespace {

constexpr std::size_t kMaxSegments = 4096;
constexpr int kMaxSegmentSize = 1 << 20;

std::string describe(const Segment& s) {
  return fmt::format("{} ({}{}{})", s.name, s.size, s.unit.empty() ? "" : " ", s.unit);
}

}  // namespace

Segment Segment::uniform(std::string name, int size, std::string unit, double low, double high, std::string meaning,
                         std::vector<int> shape) {
  Segment s;
  s.name = std::move(name);
  s.size = size;
  s.unit = std::move(unit);
  s.low.assign(std::size_t(size), float(low));
  s.high.assign(std::size_t(size), float(high));
  s.meaning = std::move(meaning);
  s.shape = shape.empty() ? std::vector<int>{size} : std::move(shape);
  return s;
}

int observation_size(std::span<const Segment> segments) {
  return segments.empty() ? 0 : segments.back().offset + segments.back().size;
}

void lay_out(std::span<Segment> segments) {
  int at = 0;
  for (Segment& s : segments) {
    s.offset = at;
    at += s.size;
  }
}

nlohmann::json segments_to_json(std::span<const Segment> segments) {
  nlohmann::json out = nlohmann::json::array();
  for (const Segment& s : segments) out.push_back({{"name", s.name}, {"size", s.size}, {"unit", s.unit}});
  return out;
}

std::vector<Segment> segments_from_json(const nlohmann::json& j) {
  if (!j.is_array()) throw std::invalid_argument("observation: expects a list of segments");
  if (j.size() > kMaxSegments) {
    throw std::invalid_argument(fmt::format("observation: {} segments, at most {}", j.size(), kMaxSegments));
  }
  std::vector<Segment> out;
  for (std::size_t k = 0; k < j.size(); ++k) {
    const nlohmann::json& e = j[k];
    const auto field = [k](const char* key) { return fmt::format("observation[{}].{}", k, key); };
    if (!e.is_object()) throw std::invalid_argument(fmt::format("observation[{}]: expects {{\"name\", \"size\", \"unit\"}}", k));
    const auto it_name = e.find("name"), it_size = e.find("size"), it_unit = e.find("unit");
    if (it_name == e.end() || !it_name->is_string() || it_name->get_ref<const std::string&>().empty() ||
        it_name->get_ref<const std::string&>().size() > 80) {
      throw std::invalid_argument(field("name") + ": expects a name of 1 to 80 characters");
    }
    if (it_size == e.end() || !it_size->is_number_integer() || it_size->get<long long>() < 1 ||
        it_size->get<long long>() > kMaxSegmentSize) {
      throw std::invalid_argument(field("size") + fmt::format(": expects an integer in [1, {}]", kMaxSegmentSize));
    }
    if (it_unit == e.end() || !it_unit->is_string() || it_unit->get_ref<const std::string&>().size() > 8) {
      throw std::invalid_argument(field("unit") + ": expects a unit of at most 8 characters (\"\" for none)");
    }
    Segment s;
    s.name = it_name->get<std::string>();
    s.size = it_size->get<int>();
    s.unit = it_unit->get<std::string>();
    s.shape = {s.size};
    out.push_back(std::move(s));
  }
  lay_out(out);
  return out;
}

std::optional<std::string> first_difference(std::span<const Segment> a, std::span<const Segment> b) {
  const std::size_t n = std::max(a.size(), b.size());
  for (std::size_t k = 0; k < n; ++k) {
    if (k >= a.size()) return fmt::format("segment {}: none where the game has {}", k, describe(b[k]));
    if (k >= b.size()) return fmt::format("segment {}: {} where the game has none", k, describe(a[k]));
    if (a[k].name != b[k].name || a[k].size != b[k].size || a[k].unit != b[k].unit) {
      return fmt::format("segment {}: {} where the game has {}", k, describe(a[k]), describe(b[k]));
    }
  }
  return std::nullopt;
}

}  // namespace peg3d::sense
