// core/markup.h: text from a user's file in XML/HTML element content and attributes, and
// JSON inside an HTML <script> element.
#include "alloycolor/core/markup.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

namespace alloycolor {
namespace {

TEST(EscapeXml, EscapesTheFiveSpecialCharacters) {
  EXPECT_EQ(EscapeXml("<img src=x onerror=\"alert(1)\">"),
            "&lt;img src=x onerror=&quot;alert(1)&quot;&gt;");
  EXPECT_EQ(EscapeXml("Tom & 'Jerry'"), "Tom &amp; &#39;Jerry&#39;");
  EXPECT_EQ(EscapeXml("Au-Ag 75 at% · 18 k"), "Au-Ag 75 at% · 18 k");
}

TEST(EscapeJsonForScript, NeitherClosesTheScriptNorStartsMarkup) {
  EXPECT_EQ(EscapeJsonForScript(R"({"file":"</script><script>alert(1)</script>"})"),
            R"({"file":"\u003c/script\u003e\u003cscript\u003ealert(1)\u003c/script\u003e"})");
  EXPECT_EQ(EscapeJsonForScript(R"(["<!--", "a && b"])"), R"(["\u003c!--", "a \u0026\u0026 b"])");
  // U+2028 and U+2029 (UTF-8 E2 80 A8, E2 80 A9); other E2 80 xx characters stay.
  EXPECT_EQ(EscapeJsonForScript("\"a\xE2\x80\xA8"
                                "b\xE2\x80\xA9"
                                "c\xE2\x80\x94\""),
            "\"a\\u2028b\\u2029c\xE2\x80\x94\"");
}

TEST(EscapeJsonForScript, ParsesToTheSameValue) {
  const nlohmann::json doc = {{"name", "<img src=x onerror=alert(1)>"},
                              {"path", "/tmp/\"quoted\" & 'single'/</script>"},
                              {"line ends",
                               "a\xE2\x80\xA8"
                               "b\xE2\x80\xA9"
                               "c"},
                              {"numbers", {0.5, -1e-300, 12}}};
  const std::string escaped = EscapeJsonForScript(doc.dump());
  for (const char* bad : {"<", ">", "&", "\xE2\x80\xA8", "\xE2\x80\xA9"}) {
    EXPECT_EQ(escaped.find(bad), std::string::npos) << bad;
  }
  EXPECT_EQ(nlohmann::json::parse(escaped), doc);
}

}  // namespace
}  // namespace alloycolor
