#pragma once
// The first line of defence for every text file a user hands peg3d (maps, configurations, policies, collision
// cases): it must be a regular file of bounded size, and nested no deeper than a parser can take without
// exhausting its stack. Everything here throws InputError naming the file (and the line, where there is one).

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace peg3d {

/// Largest text input read (maps, configurations, policies, cases, motion files): a policy of the largest
/// configuration is a few MB; nothing legitimate comes near this.
inline constexpr std::size_t kMaxTextFileBytes = std::size_t{64} << 20;
/// Deepest nesting of lists and mappings accepted in JSON and YAML (peg3d's own files nest at most 4 deep).
inline constexpr int kMaxNestingDepth = 64;

/// The whole content of a regular file of at most `max_bytes` (a FIFO, a device such as /dev/zero or a
/// directory is refused before anything is read). `what` names the kind of file in messages.
std::string read_input_file(const std::filesystem::path& file, std::string_view what,
                            std::size_t max_bytes = kMaxTextFileBytes);

/// Parses JSON text; a syntax error or nesting deeper than kMaxNestingDepth is an InputError naming the file
/// and the line.
nlohmann::json parse_json_text(std::string_view text, const std::filesystem::path& file);

/// The 1-based line of `field` in well-formed JSON text: where its key (or, for "list[3]", its element)
/// starts. Fields are dotted paths with indices, as InputError::field() writes them: "pursuer.speed",
/// "channels[0].actor[17]". 0 when the text holds no such field.
int json_line_of(std::string_view text, std::string_view field);

/// A JSON value as a message quotes it: its text, shortened to about 40 characters.
std::string brief(const nlohmann::json& value);

}  // namespace peg3d
