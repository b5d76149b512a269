#include "core/error.hpp"

#include <fmt/format.h>

namespace peg3d {

std::string format_input_error(const std::filesystem::path& file, int line, const std::string& field,
                               const std::string& message) {
  std::string where = file.empty() ? std::string() : file.string();
  if (line > 0) where += fmt::format(":{}", line);
  std::string out = where.empty() ? std::string() : where + ": ";
  if (!field.empty()) out += field + ": ";
  return out + message;
}

std::string shown(std::string_view text) {
  constexpr std::size_t kMax = 40;
  std::string out = text.size() <= kMax ? std::string(text) : std::string(text.substr(0, kMax - 3)) + "...";
  // Binary garbage must not reach a terminal as control bytes.
  for (char& c : out) {
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) c = '?';
  }
  return out;
}

InputError::InputError(const std::string& message) : std::runtime_error(message), message_(message) {}

InputError::InputError(std::filesystem::path file, int line, std::string field, const std::string& message)
    : std::runtime_error(format_input_error(file, line, field, message)),
      message_(message),
      file_(std::move(file)),
      line_(line),
      field_(std::move(field)) {}

InputError::InputError(Preformatted, const std::string& message, std::filesystem::path file, int line,
                       std::string field)
    : std::runtime_error(message), message_(message), file_(std::move(file)), line_(line), field_(std::move(field)) {}

}  // namespace peg3d
