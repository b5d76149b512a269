#pragma once
// The viewer file: one self-contained HTML page (docs/viewer.md) made of the viewer's template, style and
// script, three.js and its OrbitControls (Debian's libjs-three, staged beside the viewer's files at build
// time), and one replay's data. Everything is inlined, so the page opens from disk with no server and
// fetches nothing.

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

namespace peg3d::view {

/// The viewer's scripts, by concern (assets/viewer/common.js's header says what each holds), in the order the
/// page inlines them, one after the other inside one function scope of the template.
inline constexpr const char* kViewerScripts[] = {"common.js", "replay.js", "scene.js", "timeline.js", "panels.js",
                                                 "main.js"};

/// The texts a viewer file is assembled from.
struct ViewerAssets {
  std::string html;            ///< viewer.html, the template with the placeholders below
  std::string css;             ///< viewer.css
  std::string js;              ///< the viewer's scripts (kViewerScripts), in order, one after the other
  std::string three;           ///< three.min.js
  std::string orbit_controls;  ///< OrbitControls.js (non-module build)

  /// Reads viewer.html, viewer.css, the scripts of kViewerScripts, three.min.js and OrbitControls.js from
  /// `dir`. Throws std::runtime_error naming the missing file (an installation problem, not the user's input).
  static ViewerAssets load(const std::filesystem::path& dir);
};

/// The page: the template with @TITLE@ (HTML-escaped `title`), the style, the scripts and the replay (every
/// '<' of the JSON written as \u003c, so no text in it can end its script element) filled in.
std::string viewer_html(const ViewerAssets& assets, const nlohmann::json& replay, const std::string& title);

/// Writes viewer_html() to `file` atomically (a complete page or none).
void write_viewer_html(const std::filesystem::path& file, const ViewerAssets& assets, const nlohmann::json& replay,
                       const std::string& title);

}  // namespace peg3d::view
