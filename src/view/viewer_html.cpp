#include "view/viewer_html.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "core/atomic_file.hpp"
#include "game/observation.hpp"

namespace peg3d::view {
namespace {

std::string slurp(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error("viewer file missing: " + file.string() + " (is libjs-three installed? see README)");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Fills each placeholder of the template, found in the template alone (never in what was filled in), so
// text that happens to look like a placeholder stays as it is. Each must appear exactly once: anything else
// is a broken installation.
std::string filled(const std::string& tmpl, std::vector<std::pair<std::string, std::string>> fills) {
  std::vector<std::pair<std::size_t, std::size_t>> at;  // (position in the template, index in fills)
  for (std::size_t i = 0; i < fills.size(); ++i) {
    const std::string& token = fills[i].first;
    const std::size_t p = tmpl.find(token);
    if (p == std::string::npos || tmpl.find(token, p + token.size()) != std::string::npos) {
      throw std::runtime_error("viewer template: placeholder " + token + " must appear exactly once");
    }
    at.emplace_back(p, i);
  }
  std::sort(at.begin(), at.end());
  std::string page;
  std::size_t from = 0;
  for (const auto& [p, i] : at) {
    if (p < from) throw std::runtime_error("viewer template: placeholders overlap");
    page.append(tmpl, from, p - from);
    page += fills[i].second;
    from = p + fills[i].first.size();
  }
  page.append(tmpl, from, std::string::npos);
  return page;
}

std::string html_escaped(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

// A script's text must not close its element early.
const std::string& script_text(const std::string& text, const char* what) {
  if (text.find("</script") != std::string::npos) throw std::runtime_error(std::string(what) + " contains </script");
  return text;
}

// What the page names from the library's tables rather than its own copies: the percept entries' labels and
// units (game::kObservationEntries), as [[label, unit], ...] under "inputs".
std::string vocabulary_json() {
  nlohmann::json inputs = nlohmann::json::array();
  for (int k = 0; k < game::kPerceptEntries; ++k) {
    inputs.push_back({game::kObservationEntries[std::size_t(k)].meaning, game::kObservationEntries[std::size_t(k)].unit});
  }
  return nlohmann::json{{"inputs", inputs}}.dump();
}

}  // namespace

ViewerAssets ViewerAssets::load(const std::filesystem::path& dir) {
  std::string js;
  for (const char* script : kViewerScripts) js += slurp(dir / script) + "\n";
  return {slurp(dir / "viewer.html"), slurp(dir / "viewer.css"), js, slurp(dir / "three.min.js"),
          slurp(dir / "OrbitControls.js")};
}

std::string viewer_html(const ViewerAssets& assets, const nlohmann::json& replay, const std::string& title) {
  std::string data;
  // Replayed text (titles, file names) may hold anything; '<' only occurs inside JSON strings, where
  // \u003c means the same.
  for (char c : replay.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace)) {
    if (c == '<') data += "\\u003c";
    else data += c;
  }
  return filled(assets.html, {{"@TITLE@", html_escaped(title)},
                               {"/*@VIEWER_CSS@*/", assets.css},
                               {"/*@THREE_JS@*/", script_text(assets.three, "three.min.js")},
                               {"/*@ORBIT_CONTROLS_JS@*/", script_text(assets.orbit_controls, "OrbitControls.js")},
                               {"@REPLAY_JSON@", data},
                               {"@VOCABULARY_JSON@", vocabulary_json()},
                               {"/*@VIEWER_JS@*/", script_text(assets.js, "the viewer's scripts")}});
}

void write_viewer_html(const std::filesystem::path& file, const ViewerAssets& assets, const nlohmann::json& replay,
                       const std::string& title) {
  write_file_atomically(file, viewer_html(assets, replay, title));
}

}  // namespace peg3d::view
