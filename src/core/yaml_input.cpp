#include "core/yaml_input.hpp"

#include <yaml-cpp/depthguard.h>

#include "core/error.hpp"

namespace peg3d {
namespace {

// yaml-cpp quotes the offending byte, which in a binary file may be a control character.
std::string printable(std::string text) {
  for (char& c : text) {
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) c = '?';
  }
  return text;
}

}  // namespace

YAML::Node parse_yaml_text(const std::string& text, const std::filesystem::path& file) {
  try {
    return YAML::Load(text);
  } catch (const YAML::DeepRecursion& e) {
    // yaml-cpp's own message for this is "bad file".
    throw InputError(file, e.mark.line >= 0 ? e.mark.line + 1 : 0, "",
                     "nested too deeply (more than " + std::to_string(e.depth() - 1) + " levels)");
  } catch (const YAML::Exception& e) {
    throw InputError(file, e.mark.line >= 0 ? e.mark.line + 1 : 0, "", "YAML syntax error: " + printable(e.msg));
  }
}

}  // namespace peg3d
