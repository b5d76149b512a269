#include "world/map/mesh_file_checks.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/input_files.hpp"

namespace peg3d::world {
namespace {

namespace fs = std::filesystem;

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

[[noreturn]] void refuse(const fs::path& file, const std::string& why) {
  throw MeshError(fmt::format("mesh file '{}' {}", file.string(), why));
}

// Bodies are walked (list lengths, face indices) only in files up to this size; larger ones go to the bounded
// import with their headers checked.
constexpr std::size_t kMaxWalkedBytes = std::size_t{256} << 20;

std::string read_prefix(const fs::path& file, std::size_t n) {
  std::ifstream in(file, std::ios::binary);
  std::string s(n, '\0');
  in.read(s.data(), static_cast<std::streamsize>(n));
  s.resize(static_cast<std::size_t>(in.gcount()));
  return s;
}

// A decimal count as a header writes it; false for anything else (signs, exponents, more than 18 digits).
bool parse_count(const std::string& word, std::uint64_t& out) {
  if (word.empty() || word.size() > 18 || word.find_first_not_of("0123456789") != std::string::npos) return false;
  out = std::stoull(word);
  return true;
}

// A decimal number as text formats write them (sign, digits, point, exponent; or nan, inf).
bool is_number(std::string_view t) {
  if (t.empty() || t.size() > 64) return false;
  const std::string text(t);
  char* end = nullptr;
  (void)std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size();
}

// ---- PLY: element counts times the smallest size of one element must fit in the body. ----

struct PlyProperty {
  int size = 0;        // bytes of a scalar, or of a list's items
  int count_size = 0;  // bytes of a list's count; 0 for a scalar
};
struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::uint64_t min_bytes = 0;  // of one element
  std::vector<PlyProperty> properties;
};
struct PlyHeader {
  bool ascii = true;
  std::vector<PlyElement> elements;
};

int ply_type_size(const fs::path& file, const std::string& t) {
  static const std::array<std::pair<const char*, int>, 16> kSizes{{{"char", 1}, {"int8", 1}, {"uchar", 1}, {"uint8", 1},
                                                                   {"short", 2}, {"int16", 2}, {"ushort", 2}, {"uint16", 2},
                                                                   {"int", 4}, {"int32", 4}, {"uint", 4}, {"uint32", 4},
                                                                   {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}}};
  for (const auto& [name, bytes] : kSizes) {
    if (t == name) return bytes;
  }
  refuse(file, fmt::format("has a PLY property of unknown type '{}'", shown(t)));
}

// Where the PLY header's "end_header" line starts (npos when there is none) and where its line break is.
// assimp 5.2's PLY reader loops forever on a header cut short before "end_header", on some lines it does not
// know, and on an "end_header" not followed by a line break (the last two found by fuzzing): the header must
// be lines of the format's own keywords, ended by a line that is exactly "end_header".
std::pair<std::size_t, std::size_t> ply_header_end(std::string_view head) {
  for (std::size_t at = 0; at < head.size();) {
    const std::size_t eol = head.find('\n', at);
    if (eol == std::string::npos) break;
    std::string_view l = head.substr(at, eol - at);
    if (!l.empty() && l.back() == '\r') l.remove_suffix(1);
    if (l == "end_header") return {at, eol};
    at = eol + 1;
  }
  return {std::string::npos, std::string::npos};
}

// The header's lines (before end_header): each a keyword of the format, the elements with their counts and
// the smallest size of one.
PlyHeader read_ply_header(const fs::path& file, std::string_view header) {
  PlyHeader h;
  std::istringstream lines{std::string(header)};
  std::string line;
  bool first = true;
  while (std::getline(lines, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string key;
    words >> key;
    const bool printable = std::all_of(line.begin(), line.end(), [](char c) { return c == '\t' || (c >= 0x20 && c < 0x7f); });
    std::vector<std::string> all_words;
    for (std::istringstream again(line); again >> all_words.emplace_back();) {
    }
    all_words.pop_back();
    const std::size_t n = all_words.size();
    const bool known = first ? line == "ply"
                             : key == "comment" || key == "obj_info" ||
                                   (key == "format" && n == 3 && all_words[2] == "1.0" &&
                                    (all_words[1] == "ascii" || all_words[1] == "binary_little_endian" ||
                                     all_words[1] == "binary_big_endian")) ||
                                   (key == "element" && n == 3) ||
                                   (key == "property" && !h.elements.empty() && (n == 3 || (n == 5 && all_words[1] == "list")));
    if (!printable || !known) {
      refuse(file, fmt::format("is malformed: its PLY header has a line that is not {}", first ? "'ply' first" : "a PLY keyword"));
    }
    first = false;
    if (key == "format") {
      std::string f;
      words >> f;
      h.ascii = f == "ascii";
    } else if (key == "element") {
      PlyElement e;
      std::string count;
      words >> e.name >> count;
      if (!parse_count(count, e.count)) refuse(file, fmt::format("declares a PLY element '{}' with count '{}'", shown(e.name), shown(count)));
      h.elements.push_back(e);
    } else if (key == "property" && !h.elements.empty()) {
      std::string type;
      words >> type;
      if (type == "list") {
        std::string count_type, item_type;
        words >> count_type >> item_type;
        h.elements.back().properties.push_back({ply_type_size(file, item_type), ply_type_size(file, count_type)});
        h.elements.back().min_bytes += h.ascii ? 2 : std::uint64_t(ply_type_size(file, count_type));  // an empty list
      } else {
        h.elements.back().properties.push_back({ply_type_size(file, type), 0});
        h.elements.back().min_bytes += h.ascii ? 2 : std::uint64_t(ply_type_size(file, type));  // ascii: a digit and a space
      }
    }
  }
  return h;
}

[[noreturn]] void ply_list_too_long(const fs::path& file, const PlyElement& e, std::uint64_t i, std::uint64_t n) {
  refuse(file, fmt::format("is malformed: PLY element '{}' {} has a list of {} items, more than the file holds", shown(e.name), i, n));
}

// An ASCII body from `at`: every token a number, no list longer than the tokens that could follow.
void walk_ply_ascii(const fs::path& file, const std::string& all, std::size_t at, const PlyHeader& h) {
  const auto next_token = [&]() -> std::string_view {
    while (at < all.size() && std::isspace(static_cast<unsigned char>(all[at]))) ++at;
    const std::size_t start = at;
    while (at < all.size() && !std::isspace(static_cast<unsigned char>(all[at]))) ++at;
    return std::string_view(all).substr(start, at - start);
  };
  const auto not_a_number = [&](const PlyElement& e, std::uint64_t i, std::string_view token) {
    refuse(file, fmt::format("is malformed: PLY element '{}' {} holds '{}', not a number", shown(e.name), i, shown(token)));
  };
  for (const PlyElement& e : h.elements) {
    for (std::uint64_t i = 0; i < e.count; ++i) {
      for (const PlyProperty& p : e.properties) {
        const std::string_view token = next_token();
        if (token.empty()) return;  // cut short: the importer says so
        // assimp crashes on some bytes that are not text inside an ASCII body (found by fuzzing).
        if (!is_number(token)) not_a_number(e, i, token);
        if (p.count_size == 0) continue;
        std::uint64_t n = 0;
        if (!parse_count(std::string(token), n)) return;
        if (n > (all.size() - at) / 2 + 1) ply_list_too_long(file, e, i, n);
        for (std::uint64_t k = 0; k < n; ++k) {
          const std::string_view item = next_token();
          if (item.empty()) return;
          if (!is_number(item)) not_a_number(e, i, item);
        }
      }
    }
  }
}

// A binary body from `at`: no list count larger than the items that could follow.
void walk_ply_binary(const fs::path& file, const std::string& all, std::size_t at, const PlyHeader& h, bool big_endian) {
  for (const PlyElement& e : h.elements) {
    for (std::uint64_t i = 0; i < e.count; ++i) {
      for (const PlyProperty& p : e.properties) {
        if (p.count_size == 0) {
          at += std::size_t(p.size);
          continue;
        }
        if (at + std::size_t(p.count_size) > all.size()) return;
        std::uint64_t n = 0;
        for (int k = 0; k < p.count_size; ++k) {
          const auto byte = static_cast<unsigned char>(all[at + std::size_t(big_endian ? k : p.count_size - 1 - k)]);
          n = (n << 8) | byte;
        }
        at += std::size_t(p.count_size);
        if (n > (all.size() - at) / std::size_t(p.size)) ply_list_too_long(file, e, i, n);
        at += std::size_t(n) * std::size_t(p.size);
      }
      if (at > all.size()) return;
    }
  }
}

void check_ply(const fs::path& file, std::uintmax_t size) {
  // A file whose body is walked is read once, whole; the header is its start.
  const bool walked = size <= kMaxWalkedBytes;
  const std::string text = walked ? read_input_file(file, "mesh file", kMaxWalkedBytes) : read_prefix(file, 1 << 20);
  const std::string_view head = std::string_view(text).substr(0, std::size_t{1} << 20);
  const auto [end, body_start] = ply_header_end(head);
  if (end == std::string::npos) refuse(file, "is malformed: its PLY header has no end_header line");
  const std::uintmax_t body = size - (body_start + 1);
  const PlyHeader h = read_ply_header(file, head.substr(0, end));
  std::uint64_t need = 0;
  for (const PlyElement& e : h.elements) {
    if (e.min_bytes > 0 && e.count > body / e.min_bytes) {
      refuse(file, fmt::format("declares {} PLY elements '{}' of at least {} bytes each, but its body holds {} bytes", e.count,
                               shown(e.name), e.min_bytes, body));
    }
    need += e.count * e.min_bytes;
    if (need > body) refuse(file, fmt::format("declares PLY elements needing at least {} bytes, but its body holds {}", need, body));
  }
  // The lists' lengths are in the body: walk it, so no list asks the importer for more items than follow.
  if (!walked || body_start == std::string::npos) return;
  if (h.ascii) {
    walk_ply_ascii(file, text, body_start + 1, h);
  } else {
    walk_ply_binary(file, text, body_start + 1, h, head.find("binary_big_endian") < end);
  }
}

// ---- OFF: "OFF nv nf ne"; a vertex takes at least 6 bytes ("0 0 0\n"), a face at least 4 ("1 0\n"). ----

void check_off(const fs::path& file, std::uintmax_t size) {
  const bool walked = size <= kMaxWalkedBytes;
  const std::string text = walked ? read_input_file(file, "mesh file", kMaxWalkedBytes) : read_prefix(file, 4096);
  std::istringstream in(text.substr(0, 4096));
  std::vector<std::string> words;
  std::string line;
  while (words.size() < 4 && std::getline(in, line)) {
    if (const std::size_t hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::istringstream w(line);
    std::string word;
    while (words.size() < 4 && w >> word) words.push_back(word);
  }
  if (words.empty() || words[0].find("OFF") == std::string::npos) return;  // the importer says what is wrong
  std::uint64_t nv = 0, nf = 0;
  if (words.size() < 3 || !parse_count(words[1], nv) || !parse_count(words[2], nf)) {
    refuse(file, "is malformed: its OFF header needs vertex and face counts");
  }
  if (nv > size / 6 || nf > size / 4 || nv * 6 + nf * 4 > size) {
    refuse(file, fmt::format("declares {} vertices and {} faces, more than its {} bytes can hold", nv, nf, size));
  }
  // assimp clamps a face's out-of-range index to the last vertex, making up a triangle: refuse it instead.
  if (!walked) return;
  std::istringstream all(text);
  std::uint64_t skipped = 0, face = 0;
  bool counts_read = false;
  while (std::getline(all, line) && face < nf) {
    if (const std::size_t hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::istringstream w(line);
    std::string first;
    if (!(w >> first)) continue;
    if (!counts_read) {  // the header's lines: "OFF" (maybe with the counts after it), then the counts
      counts_read = first.find("OFF") == std::string::npos || static_cast<bool>(w >> first);
      continue;
    }
    if (skipped < nv) {
      ++skipped;
      continue;
    }
    std::uint64_t n = 0, index = 0;
    if (!parse_count(first, n)) return;  // the importer reports what it makes of it
    for (std::uint64_t k = 0; k < n && w >> first; ++k) {
      if (!parse_count(first, index)) return;
      if (index >= nv) refuse(file, fmt::format("is malformed: face {} names vertex {} of {}", face, index, nv));
    }
    ++face;
  }
}

// ---- binary STL: an 80-byte header, a facet count, 50 bytes per facet. ----

void check_stl(const fs::path& file, std::uintmax_t size) {
  const std::string head = read_prefix(file, 84);
  std::size_t i = 0;
  while (i < head.size() && std::isspace(static_cast<unsigned char>(head[i]))) ++i;
  if (head.compare(i, 5, "solid") == 0 || head.size() < 84) return;  // ASCII: counts are not declared
  std::uint32_t n = 0;
  std::memcpy(&n, head.data() + 80, 4);  // little-endian, as the format is and x86 and ARM are
  if (84 + 50 * std::uintmax_t(n) != size) {
    refuse(file, fmt::format("declares {} binary STL triangles ({} bytes), but has {} bytes", n, 84 + 50 * std::uintmax_t(n), size));
  }
}

// ---- glTF 2: buffers, views and accessors against their data; nodes a tree; external files safe. ----

std::uint64_t as_count(const nlohmann::json& j, const fs::path& file, const std::string& field) {
  if (!j.is_number_unsigned() && !(j.is_number_integer() && j.get<std::int64_t>() >= 0)) {
    refuse(file, fmt::format("has {} = {}, expected a non-negative integer", field, brief(j)));
  }
  return j.get<std::uint64_t>();
}

const nlohmann::json& list(const nlohmann::json& doc, const char* key, const fs::path& file) {
  static const nlohmann::json kEmpty = nlohmann::json::array();
  const auto it = doc.find(key);
  if (it == doc.end()) return kEmpty;
  if (!it->is_array()) refuse(file, fmt::format("has '{}' that is not a list", key));
  for (const auto& item : *it) {
    if (!item.is_object()) refuse(file, fmt::format("has an entry of '{}' that is not an object", key));
  }
  return *it;
}

// A binary glTF's container: its JSON chunk (returned) and the size of its BIN chunk (0 when none).
std::string_view glb_chunks(const fs::path& file, const std::string& bytes, std::uint64_t& bin_chunk) {
  const auto u32 = [&](std::size_t at) {
    std::uint32_t v = 0;
    if (at + 4 <= bytes.size()) std::memcpy(&v, bytes.data() + at, 4);
    return v;
  };
  if (bytes.size() < 20 || bytes.compare(0, 4, "glTF") != 0) refuse(file, "is not a binary glTF (no 'glTF' header)");
  if (u32(8) != bytes.size()) refuse(file, fmt::format("declares {} bytes in its glTF header, but has {}", u32(8), bytes.size()));
  const std::uint64_t json_length = u32(12);
  if (json_length > bytes.size() - 20) refuse(file, fmt::format("declares a JSON chunk of {} bytes, beyond its end", json_length));
  const std::size_t bin_at = 20 + json_length;
  if (bin_at + 8 <= bytes.size()) {
    bin_chunk = u32(bin_at);
    if (bin_chunk > bytes.size() - bin_at - 8) refuse(file, fmt::format("declares a BIN chunk of {} bytes, beyond its end", bin_chunk));
  }
  return std::string_view(bytes).substr(20, json_length);
}

// Each buffer's declared length against its data (the BIN chunk, a data: URI, or a safe file beside the mesh).
std::vector<std::uint64_t> gltf_buffers(const fs::path& file, const nlohmann::json& doc, std::uint64_t bin_chunk) {
  std::vector<std::uint64_t> buffer_bytes;
  const nlohmann::json& buffers = list(doc, "buffers", file);
  for (std::size_t b = 0; b < buffers.size(); ++b) {
    const std::string field = fmt::format("buffers[{}]", b);
    const std::uint64_t declared = as_count(buffers[b].value("byteLength", nlohmann::json(0)), file, field + ".byteLength");
    std::uint64_t available = 0;
    const auto uri = buffers[b].find("uri");
    if (uri == buffers[b].end()) {
      available = bin_chunk;
    } else if (!uri->is_string()) {
      refuse(file, field + ".uri is not a string");
    } else if (const std::string& u = uri->get_ref<const std::string&>(); u.rfind("data:", 0) == 0) {
      const std::size_t comma = u.find(',');
      available = comma == std::string::npos ? 0 : (u.size() - comma - 1) / 4 * 3 + 2;
    } else {
      const fs::path ref = file.parent_path() / u;
      if (!is_safe_mesh_reference(file, ref)) {
        refuse(file, fmt::format("has {}.uri '{}' that is not a regular file inside the mesh's folder", field, shown(u)));
      }
      available = fs::file_size(ref);
    }
    if (declared > available) {
      refuse(file, fmt::format("declares {}.byteLength = {}, but its data holds {} bytes", field, declared, available));
    }
    buffer_bytes.push_back(declared);
  }
  return buffer_bytes;
}

// Views inside their buffers, and accessors' counts within their views.
void gltf_views_and_accessors(const fs::path& file, const nlohmann::json& doc, const std::vector<std::uint64_t>& buffer_bytes) {
  std::vector<std::uint64_t> view_bytes;
  const nlohmann::json& views = list(doc, "bufferViews", file);
  for (std::size_t v = 0; v < views.size(); ++v) {
    const std::string field = fmt::format("bufferViews[{}]", v);
    const std::uint64_t buffer = as_count(views[v].value("buffer", nlohmann::json(-1)), file, field + ".buffer");
    const std::uint64_t offset = as_count(views[v].value("byteOffset", nlohmann::json(0)), file, field + ".byteOffset");
    const std::uint64_t length = as_count(views[v].value("byteLength", nlohmann::json(-1)), file, field + ".byteLength");
    if (buffer >= buffer_bytes.size() || offset > buffer_bytes[buffer] || length > buffer_bytes[buffer] - offset) {
      refuse(file, fmt::format("has {} outside its buffer", field));
    }
    view_bytes.push_back(length);
  }
  const nlohmann::json& accessors = list(doc, "accessors", file);
  for (std::size_t a = 0; a < accessors.size(); ++a) {
    const std::string field = fmt::format("accessors[{}]", a);
    const std::uint64_t count = as_count(accessors[a].value("count", nlohmann::json(-1)), file, field + ".count");
    // Without a view an accessor is count zeros, allocated whole: bound it like the largest real one.
    const std::uint64_t limit = accessors[a].contains("bufferView")
                                    ? [&] {
                                        const std::uint64_t v = as_count(accessors[a]["bufferView"], file, field + ".bufferView");
                                        if (v >= view_bytes.size()) refuse(file, fmt::format("has {}.bufferView out of range", field));
                                        return view_bytes[v];
                                      }()
                                    : kMaxMeshFileBytes;
    if (count > limit) refuse(file, fmt::format("declares {}.count = {}, more than its data can hold", field, count));
  }
}

// Nodes: every child index valid, no node the child of two parents or of itself, no deeper than 64.
void gltf_node_tree(const fs::path& file, const nlohmann::json& doc) {
  const nlohmann::json& nodes = list(doc, "nodes", file);
  std::vector<int> parent(nodes.size(), -1);
  for (std::size_t n = 0; n < nodes.size(); ++n) {
    const auto children = nodes[n].find("children");
    if (children == nodes[n].end()) continue;
    if (!children->is_array()) refuse(file, fmt::format("has nodes[{}].children that is not a list", n));
    for (const auto& c : *children) {
      const std::uint64_t child = as_count(c, file, fmt::format("nodes[{}].children", n));
      if (child >= nodes.size()) refuse(file, fmt::format("has nodes[{}] with child {} out of range", n, child));
      if (child == n || parent[child] >= 0) {
        refuse(file, fmt::format("has node {} as a child twice or of itself: the node hierarchy must be a tree", child));
      }
      parent[child] = static_cast<int>(n);
    }
  }
  for (std::size_t n = 0; n < nodes.size(); ++n) {
    int depth = 0;
    for (int at = static_cast<int>(n); parent[std::size_t(at)] >= 0; at = parent[std::size_t(at)]) {
      if (++depth > 64) refuse(file, fmt::format("nests node {} more than 64 deep (or in a cycle)", n));
    }
  }
}

void check_gltf(const fs::path& file, std::uintmax_t size, bool binary) {
  if (size > kMaxWalkedBytes) return;  // larger glTF files go to the bounded import unchecked
  const std::string bytes = read_input_file(file, "mesh file", kMaxWalkedBytes);
  std::uint64_t bin_chunk = 0;
  const std::string_view json_text = binary ? glb_chunks(file, bytes, bin_chunk) : std::string_view(bytes);
  nlohmann::json doc;
  try {
    doc = parse_json_text(json_text, file);
  } catch (const InputError& e) {
    const std::string& m = e.message();  // its "last read" can quote a whole base64 buffer
    refuse(file, "is not valid glTF JSON: " + (m.size() <= 160 ? m : m.substr(0, 157) + "..."));
  }
  if (!doc.is_object()) refuse(file, "is not a glTF document (expected a JSON object)");
  gltf_views_and_accessors(file, doc, gltf_buffers(file, doc, bin_chunk));
  gltf_node_tree(file, doc);
}

// ---- 3DS: chunks (id u16, length u32 including the 6-byte header) nested inside their parents. ----

void check_3ds_chunks(const fs::path& file, const std::string& b, std::size_t at, std::size_t end, int depth) {
  if (depth > 16) refuse(file, "nests 3DS chunks more than 16 deep");
  std::uint16_t vertices = 0;  // of the triangle mesh whose chunks these are (its vertex list comes first)
  while (at + 6 <= end) {
    std::uint16_t id = 0;
    std::uint32_t length = 0;
    std::memcpy(&id, b.data() + at, 2);
    std::memcpy(&length, b.data() + at + 2, 4);
    if (length < 6 || length > end - at) {
      refuse(file, fmt::format("has a 3DS chunk 0x{:04X} at byte {} of {} bytes, beyond its parent (which ends at byte {})", id,
                               at, length, end));
    }
    const std::size_t data = at + 6, stop = at + length;
    std::uint16_t count = 0;
    if (stop - data >= 2) std::memcpy(&count, b.data() + data, 2);
    switch (id) {
      case 0x4D4D:  // main
      case 0x3D3D:  // editor
      case 0x4100:  // triangle mesh
        check_3ds_chunks(file, b, data, stop, depth + 1);
        break;
      case 0x4000: {  // named object: a zero-terminated name, then chunks
        const std::size_t name_end = b.find('\0', data);
        if (name_end == std::string::npos || name_end >= stop) refuse(file, fmt::format("has a 3DS object at byte {} without a name", at));
        check_3ds_chunks(file, b, name_end + 1, stop, depth + 1);
        break;
      }
      case 0x4110:  // vertices: a count, then 3 floats each
        if (2 + std::size_t(count) * 12 > stop - data) refuse(file, fmt::format("declares {} 3DS vertices in a chunk of {} bytes", count, length));
        vertices = count;
        break;
      case 0x4120:  // faces: a count, then 3 vertex indices and a flag word each
        if (2 + std::size_t(count) * 8 > stop - data) refuse(file, fmt::format("declares {} 3DS faces in a chunk of {} bytes", count, length));
        // assimp clamps an out-of-range index to the last vertex, making up a triangle: refuse it instead.
        for (std::size_t f = 0; f < count; ++f) {
          for (std::size_t k = 0; k < 3; ++k) {
            std::uint16_t index = 0;
            std::memcpy(&index, b.data() + data + 2 + f * 8 + k * 2, 2);
            if (index >= vertices) refuse(file, fmt::format("is malformed: 3DS face {} names vertex {} of {}", f, index, vertices));
          }
        }
        break;
      default:
        break;
    }
    at = stop;
  }
}

void check_3ds(const fs::path& file, std::uintmax_t size) {
  if (size > kMaxWalkedBytes) return;
  const std::string bytes = read_input_file(file, "mesh file", kMaxWalkedBytes);
  check_3ds_chunks(file, bytes, 0, bytes.size(), 0);
}

}  // namespace

bool is_accepted_mesh_extension(std::string_view extension) {
  for (const char* e : {".obj", ".stl", ".ply", ".off", ".gltf", ".glb", ".3ds"}) {
    if (extension == e) return true;
  }
  return false;
}

bool is_safe_mesh_reference(const fs::path& mesh, const fs::path& reference) {
  std::error_code ec;
  const fs::path folder = fs::weakly_canonical(fs::absolute(mesh, ec).parent_path(), ec);
  if (ec) return false;
  const fs::path target = fs::weakly_canonical(fs::absolute(reference, ec), ec);
  if (ec || !fs::is_regular_file(target, ec)) return false;
  const auto [f, t] = std::mismatch(folder.begin(), folder.end(), target.begin(), target.end());
  return f == folder.end();
}

void check_mesh_declarations(const fs::path& file) {
  const std::string ext = lower(file.extension().string());
  if (!is_accepted_mesh_extension(ext)) {
    refuse(file, fmt::format("is not of a format peg3d imports (by its extension '{}'); use {}", shown(ext), kAcceptedMeshFormats));
  }
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(file, ec);
  if (ec) refuse(file, "cannot be read: " + ec.message());
  if (size > kMaxMeshFileBytes) refuse(file, fmt::format("is {} bytes, more than the {} this build reads", size, kMaxMeshFileBytes));
  if (ext == ".ply") check_ply(file, size);
  if (ext == ".off") check_off(file, size);
  if (ext == ".stl") check_stl(file, size);
  if (ext == ".gltf" || ext == ".glb") check_gltf(file, size, ext == ".glb");
  if (ext == ".3ds") check_3ds(file, size);
}

}  // namespace peg3d::world
