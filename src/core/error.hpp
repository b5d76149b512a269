#pragma once
// One family of errors for everything a user can get wrong: maps, meshes, configurations, policy files and
// command-line flags. The programs exit with status 2 for exactly these (and 1 for anything else), so a
// caller can tell "fix your input" from "peg3d failed". Each names where the problem is: the file, the line
// (1-based, 0 when unknown) and the dotted field when they are known.

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

namespace peg3d {

class InputError : public std::runtime_error {
 public:
  /// A problem with no particular file (a flag, a value set in code).
  explicit InputError(const std::string& message);
  /// what() reads "FILE:LINE: FIELD: message", leaving out the parts that are empty or 0.
  InputError(std::filesystem::path file, int line, std::string field, const std::string& message);
  /// what() is `message` exactly, which already says where (the command line's messages do).
  struct Preformatted {};
  InputError(Preformatted, const std::string& message, std::filesystem::path file, int line, std::string field);

  const std::filesystem::path& file() const noexcept { return file_; }
  /// 1-based line in file(), 0 when unknown.
  int line() const noexcept { return line_; }
  /// Dotted path of the offending field, e.g. "obstacles[2].radius"; empty when there is none.
  const std::string& field() const noexcept { return field_; }
  /// The problem alone, without the place (for a preformatted error: the whole text).
  const std::string& message() const noexcept { return message_; }

 private:
  std::string message_;
  std::filesystem::path file_;
  int line_ = 0;
  std::string field_;
};

/// A piece of the user's text as a message quotes it: at most 40 characters ("..." marks a cut), bytes that
/// are not printable ASCII as '?', so neither a megabyte-long key nor binary garbage can flood a terminal.
std::string shown(std::string_view text);

/// "FILE:LINE: FIELD: message" with the empty parts left out (the format of InputError::what()).
std::string format_input_error(const std::filesystem::path& file, int line, const std::string& field,
                               const std::string& message);

}  // namespace peg3d
