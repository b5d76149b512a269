// The viewer page: the template's placeholders filled once each with the assets and the replay, nothing in
// the replay able to end its script element or be taken for a placeholder, and a broken template refused.
#include "view/viewer_html.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace peg3d::view {
namespace {

ViewerAssets tiny() {
  return {"<title>@TITLE@</title><style>/*@VIEWER_CSS@*/</style><script>/*@THREE_JS@*/</script>"
          "<script>/*@ORBIT_CONTROLS_JS@*/</script><script id=\"peg-replay\" type=\"application/json\">@REPLAY_JSON@"
          "</script><script id=\"peg-vocabulary\" type=\"application/json\">@VOCABULARY_JSON@</script>"
          "<script>/*@VIEWER_JS@*/</script>",
          "body{}", "viewer();", "var THREE={};", "THREE.OrbitControls=1;"};
}

std::size_t count(const std::string& s, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = s.find(what); at != std::string::npos; at = s.find(what, at + 1)) ++n;
  return n;
}

TEST(ViewViewerHtml, FillsEveryPlaceholderOnce) {
  const std::string page = viewer_html(tiny(), {{"frames", 3}}, "S1 peg3d");
  EXPECT_EQ(page,
            "<title>S1 peg3d</title><style>body{}</style><script>var THREE={};</script>"
            "<script>THREE.OrbitControls=1;</script><script id=\"peg-replay\" type=\"application/json\">{\"frames\":3}"
            "</script><script id=\"peg-vocabulary\" type=\"application/json\">{\"inputs\":[[\"d to opponent\",\"m\"],"
            "[\"opponent azimuth error\",\"rad\"],[\"opponent elevation error\",\"rad\"],[\"d to obstacle\",\"m\"],"
            "[\"obstacle azimuth error\",\"rad\"],[\"obstacle elevation error\",\"rad\"]]}</script>"
            "<script>viewer();</script>");
}

TEST(ViewViewerHtml, NoTextOfTheReplayCanCloseItsScriptOrFillAPlaceholder) {
  const std::string nasty = "</script><script>alert(1)</script>/*@VIEWER_JS@*/ @TITLE@";
  const std::string page = viewer_html(tiny(), {{"title", nasty}}, nasty);
  EXPECT_EQ(count(page, "</script>"), 5u);  // the page's own five scripts, nothing more
  EXPECT_EQ(count(page, "viewer();"), 1u);
  EXPECT_NE(page.find("&lt;/script&gt;"), std::string::npos);  // the title, escaped
  // The JSON still reads back as the same text.
  const std::size_t from = page.find("application/json\">") + 18;
  const std::size_t to = page.find("</script>", from);
  EXPECT_EQ(nlohmann::json::parse(page.substr(from, to - from)).at("title"), nasty);
}

TEST(ViewViewerHtml, ATemplateWithoutAPlaceholderOrWithTwoIsRefused) {
  ViewerAssets a = tiny();
  a.html.erase(a.html.find("/*@VIEWER_JS@*/"), 15);
  EXPECT_THROW(viewer_html(a, {}, "t"), std::runtime_error);
  a = tiny();
  a.html += "/*@THREE_JS@*/";
  EXPECT_THROW(viewer_html(a, {}, "t"), std::runtime_error);
}

TEST(ViewViewerHtml, AnAssetThatWouldCloseItsScriptIsRefused) {
  ViewerAssets a = tiny();
  a.js = "document.write('</script>')";
  EXPECT_THROW(viewer_html(a, {}, "t"), std::runtime_error);
}

}  // namespace
}  // namespace peg3d::view
