#include "core/input_files.hpp"

#include <fstream>
#include <system_error>
#include <vector>

#include <fmt/format.h>

#include "core/error.hpp"

namespace peg3d {

std::string read_input_file(const std::filesystem::path& file, std::string_view what, std::size_t max_bytes) {
  std::error_code ec;
  const auto status = std::filesystem::status(file, ec);
  if (ec || !std::filesystem::exists(status)) throw InputError(file, 0, "", fmt::format("{} not found", what));
  // A FIFO would block and a device such as /dev/zero never ends: only regular files are read.
  if (!std::filesystem::is_regular_file(status)) throw InputError(file, 0, "", fmt::format("{} is not a regular file", what));
  const auto size = std::filesystem::file_size(file, ec);
  if (ec) throw InputError(file, 0, "", fmt::format("cannot read {}: {}", what, ec.message()));
  if (size > max_bytes) {
    throw InputError(file, 0, "", fmt::format("{} is {} bytes, more than the {} this build reads", what, size, max_bytes));
  }
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file, 0, "", fmt::format("cannot open {}", what));
  std::string text(static_cast<std::size_t>(size), '\0');
  in.read(text.data(), static_cast<std::streamsize>(size));
  text.resize(static_cast<std::size_t>(in.gcount()));  // it may have shrunk since
  return text;
}

namespace {

int line_at(std::string_view text, std::size_t byte) {
  int line = 1;
  for (std::size_t i = 0; i < byte && i < text.size(); ++i) line += text[i] == '\n';
  return line;
}

// The byte at which the nesting of lists and objects first exceeds `limit` (strings skipped), or npos.
std::size_t too_deep_at(std::string_view text, int limit) {
  int depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') ++i;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > limit) return i;
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return std::string_view::npos;
}

// nlohmann's messages start "[json.exception.parse_error.101] ": an id for its developers, not for users.
std::string without_id(const char* what) {
  const std::string_view m(what);
  const std::size_t end = m.rfind("] ", m.find(' '));
  return std::string(m.substr(m.starts_with("[json.exception.") && end != std::string_view::npos ? end + 2 : 0));
}

}  // namespace

nlohmann::json parse_json_text(std::string_view text, const std::filesystem::path& file) {
  // nlohmann's parser is iterative, but its serializer and destructor recurse: bound the depth first.
  if (const std::size_t at = too_deep_at(text, kMaxNestingDepth); at != std::string_view::npos) {
    throw InputError(file, line_at(text, at), "", fmt::format("nested more than {} levels deep", kMaxNestingDepth));
  }
  try {
    return nlohmann::json::parse(text.begin(), text.end());
  } catch (const nlohmann::json::parse_error& e) {
    // e.byte is 1-based: the byte just read when the error was found.
    throw InputError(file, line_at(text, e.byte == 0 ? 0 : e.byte - 1), "", "not JSON: " + without_id(e.what()));
  } catch (const nlohmann::json::exception& e) {
    // A number beyond double's range ("1e999") is out_of_range.406, which carries no position.
    throw InputError(file, 0, "", "not JSON: " + without_id(e.what()));
  }
}

namespace {

// One step of a field path: a key, or an index into a list.
struct PathStep {
  std::string key;
  long index = -1;  ///< >= 0: an index
};

std::vector<PathStep> split_field(std::string_view field) {
  std::vector<PathStep> steps;
  std::size_t i = 0;
  while (i < field.size()) {
    if (field[i] == '.') {
      ++i;
    } else if (field[i] == '[') {
      const std::size_t end = field.find(']', i);
      if (end == std::string_view::npos) return {};
      long v = 0;
      for (std::size_t k = i + 1; k < end; ++k) {
        if (field[k] < '0' || field[k] > '9' || v > 100000000) return {};
        v = v * 10 + (field[k] - '0');
      }
      steps.push_back({"", v});
      i = end + 1;
    } else {
      const std::size_t end = field.find_first_of(".[", i);
      const std::string_view word = field.substr(i, end - i);
      // Configuration lists name their elements "list.3" (as --set takes them): a number is an index.
      if (word.size() <= 9 && word.find_first_not_of("0123456789") == std::string_view::npos) {
        steps.push_back({"", std::stol(std::string(word))});
      } else {
        steps.push_back({std::string(word), -1});
      }
      i = end == std::string_view::npos ? field.size() : end;
    }
  }
  return steps;
}

// Walks well-formed JSON text to the value a path names, counting lines.
class LineSeeker {
 public:
  explicit LineSeeker(std::string_view text) : s_(text) {}

  int seek(const std::vector<PathStep>& path) {
    space();
    return at_value(path, 0) ? found_ : 0;
  }

 private:
  void space() {
    while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\t' || s_[i_] == '\n' || s_[i_] == '\r')) {
      line_ += s_[i_] == '\n';
      ++i_;
    }
  }
  std::string string() {  // at '"': the raw text between the quotes
    const std::size_t start = ++i_;
    while (i_ < s_.size() && s_[i_] != '"') i_ += s_[i_] == '\\' ? 2 : 1;
    const std::string out(s_.substr(start, std::min(i_, s_.size()) - start));
    ++i_;
    return out;
  }
  void skip_value() {
    if (i_ >= s_.size()) return;
    if (s_[i_] == '"') {
      string();
      return;
    }
    if (s_[i_] != '[' && s_[i_] != '{') {
      while (i_ < s_.size() && s_[i_] != ',' && s_[i_] != ']' && s_[i_] != '}' && s_[i_] != '\n' && s_[i_] != ' ') ++i_;
      return;
    }
    int depth = 0;
    while (i_ < s_.size()) {
      const char c = s_[i_];
      if (c == '"') {
        string();
        continue;
      }
      line_ += c == '\n';
      ++i_;
      if (c == '[' || c == '{') ++depth;
      if ((c == ']' || c == '}') && --depth == 0) return;
    }
  }
  bool at_value(const std::vector<PathStep>& path, std::size_t k) {
    if (k == path.size()) {
      found_ = line_;
      return true;
    }
    if (i_ >= s_.size()) return false;
    const PathStep& want = path[k];
    if (s_[i_] == '{' && want.index < 0) {
      ++i_;
      for (;;) {
        space();
        if (i_ >= s_.size() || s_[i_] != '"') return false;
        const int key_line = line_;
        const std::string key = string();
        space();
        if (i_ >= s_.size() || s_[i_] != ':') return false;
        ++i_;
        space();
        if (key == want.key) {
          if (k + 1 == path.size()) {
            found_ = key_line;
            return true;
          }
          return at_value(path, k + 1);
        }
        skip_value();
        space();
        if (i_ >= s_.size() || s_[i_] != ',') return false;
        ++i_;
      }
    }
    if (s_[i_] == '[' && want.index >= 0) {
      ++i_;
      for (long n = 0;; ++n) {
        space();
        if (i_ >= s_.size() || s_[i_] == ']') return false;
        if (n == want.index) return at_value(path, k + 1);
        skip_value();
        space();
        if (i_ >= s_.size() || s_[i_] != ',') return false;
        ++i_;
      }
    }
    return false;
  }

  std::string_view s_;
  std::size_t i_ = 0;
  int line_ = 1;
  int found_ = 0;
};

}  // namespace

int json_line_of(std::string_view text, std::string_view field) {
  const std::vector<PathStep> path = split_field(field);
  if (path.empty() || too_deep_at(text, kMaxNestingDepth) != std::string_view::npos) return 0;
  return LineSeeker(text).seek(path);
}

std::string brief(const nlohmann::json& value) {
  constexpr std::size_t kMax = 40;
  if (value.is_array() && value.size() > 8) return fmt::format("a list of {} items", value.size());
  if (value.is_object() && value.size() > 8) return fmt::format("an object of {} keys", value.size());
  std::string text = value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  if (text.size() > kMax) text = text.substr(0, kMax - 3) + "...";
  return text;
}

}  // namespace peg3d
