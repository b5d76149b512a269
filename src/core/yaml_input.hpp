#pragma once
// YAML text from a user's file (maps, collision cases), parsed behind the same bounds as every other input
// (core/input_files.hpp). yaml-cpp's headers are needed by the readers only, so this header stands apart.

#include <filesystem>
#include <string>

#include <yaml-cpp/yaml.h>

namespace peg3d {

/// Parses YAML text; a syntax error or nesting deeper than yaml-cpp's recursion guard is an InputError naming
/// the file and the line. An empty document is a null node.
YAML::Node parse_yaml_text(const std::string& text, const std::filesystem::path& file);

}  // namespace peg3d
