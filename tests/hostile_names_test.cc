// Names from a user's files are data, never markup (OWASP XSS prevention, rule 1): a data
// set whose folder, sample file names and name hold HTML and script, and a model whose
// sample sources do, give an explorer page and a validation report in which
//  - those names appear only escaped (&lt; in HTML, \u003c in the page's JSON block, no
//    raw U+2028 or U+2029), and the JSON block still reads back as the names;
//  - headless Chromium (skipped without it) builds no element and no event handler from
//    them, runs the page to the end, and shows the names as text.
// A folder name that is not UTF-8 still gives a page.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "test_util.h"

namespace alloycolor {
namespace {

namespace fs = std::filesystem;
using testing::DataDir;
using testing::MakeTempDir;
using testing::ReadText;
using testing::RunProgram;
using testing::RunResult;
using testing::WriteText;

constexpr const char* kChromium = "/usr/bin/chromium";

// The data set's folder, its sample files (relative to it; "/" makes sub-folders) and name.
const char kFolder[] = "<img src=x onerror=alert(1)> \"dq\" 'sq' & amp";
const std::vector<std::string> kSampleFiles = {"<img src=x onerror=alert(2)>.yml",
                                               "x</script><script>alert(3)</script>.yml",
                                               "\"dq\" & 'sq' <!-- c -->.yml",
                                               "<svg onload=alert(4)>.yml",
                                               "line\u2028sep\u2029.yml",
                                               "</style><iframe src=javascript:alert(5)>.yml",
                                               "s6.yml",
                                               "s7.yml",
                                               "s8.yml",
                                               "s9.yml",
                                               "s10.yml"};
const char kDatasetName[] = "</script><b id=hostile-name onclick=alert(6)>name</b>";
// A model's sample source.
const char kModelSource[] = "<img src=x onerror=alert(7)></script><script>alert(8)</script>";

// Markup that must never reach a document unescaped; in a script, neither may U+2028 and
// U+2029 (line ends to JavaScript).
const std::vector<std::string> kRawMarkup = {"<img",          "<svg onload", "<script>alert",
                                             "<b id=hostile", "<iframe",     "<!-- c"};
const std::vector<std::string> kRawInScript = {"\u2028", "\u2029"};

std::string Lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

int Count(const std::string& text, const std::string& what) {
  int n = 0;
  for (std::size_t at = 0; (at = text.find(what, at)) != std::string::npos; at += what.size()) ++n;
  return n;
}

// The element and attribute names in serialized HTML: comments, end tags, quoted attribute
// values and the raw text of script and style elements are skipped.
struct Elements {
  std::multiset<std::string> tags;
  std::set<std::string> attributes;
};

Elements ElementsOf(const std::string& html) {
  Elements out;
  const std::string lower = Lower(html);
  const auto is_name = [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == ':';
  };
  std::size_t i = 0;
  while ((i = lower.find('<', i)) != std::string::npos) {
    if (lower.compare(i, 4, "<!--") == 0) {
      i = lower.find("-->", i);
      continue;
    }
    if (i + 1 >= lower.size() || !std::isalpha(static_cast<unsigned char>(lower[i + 1]))) {
      i = lower.find('>', i);  // an end tag or a doctype
      continue;
    }
    std::size_t j = i + 1;
    while (j < lower.size() && is_name(lower[j])) ++j;
    const std::string tag = lower.substr(i + 1, j - i - 1);
    out.tags.insert(tag);
    while (j < lower.size() && lower[j] != '>') {
      if (std::isspace(static_cast<unsigned char>(lower[j])) || lower[j] == '/') {
        ++j;
        continue;
      }
      const std::size_t name_start = j;
      while (j < lower.size() && !std::isspace(static_cast<unsigned char>(lower[j])) &&
             lower[j] != '=' && lower[j] != '>' && lower[j] != '/') {
        ++j;
      }
      out.attributes.insert(lower.substr(name_start, j - name_start));
      if (j < lower.size() && lower[j] == '=') {
        ++j;
        if (lower[j] == '"' || lower[j] == '\'') {
          j = lower.find(lower[j], j + 1) + 1;
        } else {
          while (j < lower.size() && !std::isspace(static_cast<unsigned char>(lower[j])) &&
                 lower[j] != '>') {
            ++j;
          }
        }
      }
    }
    i = j;
    if (tag == "script" || tag == "style") i = lower.find("</" + tag, i);
  }
  return out;
}

// No element or event handler from the names: every tag is one of the document's own, no
// attribute is an on... handler.
void ExpectOnlyOwnElements(const std::string& html, int scripts, const std::string& what) {
  // The tags the explorer page and the report write themselves, and tbody, which a
  // browser adds to a table.
  static const std::set<std::string> kOwn = {
      "b",     "body",  "br",      "button",  "canvas",   "caption", "circle", "clippath", "code",
      "dd",    "defs",  "details", "div",     "dl",       "dt",      "g",      "h1",       "h2",
      "h3",    "h4",    "head",    "header",  "html",     "i",       "input",  "label",    "li",
      "line",  "meta",  "p",       "polygon", "polyline", "rect",    "script", "section",  "small",
      "span",  "style", "sub",     "summary", "svg",      "table",   "td",     "text",     "th",
      "title", "tr",    "ul",      "tbody"};
  const Elements e = ElementsOf(html);
  for (const std::string& tag : std::set<std::string>(e.tags.begin(), e.tags.end())) {
    EXPECT_TRUE(kOwn.count(tag)) << what << ": <" << tag << ">";
  }
  for (const std::string& a : e.attributes) {
    EXPECT_NE(a.rfind("on", 0), 0u) << what << ": attribute " << a;
    EXPECT_NE(a, "src") << what;
  }
  EXPECT_EQ(static_cast<int>(e.tags.count("script")), scripts) << what;
}

void ExpectNoRaw(const std::vector<std::string>& raw, const std::string& html,
                 const std::string& what) {
  for (const std::string& bad : raw) {
    EXPECT_EQ(html.find(bad), std::string::npos) << what << " holds " << bad;
  }
}

// The explorer page's JSON block, as text.
std::string DataBlock(const std::string& html) {
  const std::string open = "<script type=\"application/json\" id=\"explorer-data\">";
  const std::size_t begin = html.find(open);
  if (begin == std::string::npos) return "";
  const std::size_t end = html.find("</script>", begin);
  return html.substr(begin + open.size(), end - begin - open.size());
}

std::string DumpDom(const std::string& dir, const std::string& page) {
  const std::string out = dir + "/dom.html";
  const std::string command = std::string("timeout 120 ") + kChromium +
                              " --headless --no-sandbox --disable-gpu --no-first-run "
                              "--disable-background-networking --disable-component-update "
                              "--disable-sync --user-data-dir=" +
                              dir +
                              "/chromium-profile "
                              "--dump-dom 'file://" +
                              page + "' >" + out + " 2>" + dir + "/chromium.log";
  if (std::system(command.c_str()) != 0) return "";
  return ReadText(out);
}

class HostileNames : public ::testing::Test {
 protected:
  // The bundled Au-Ag samples under the hostile names, in the hostile folder.
  static void SetUpTestSuite() {
    root_ = new std::string(MakeTempDir());
    folder_ = new std::string(*root_ + "/" + kFolder);
    const nlohmann::json bundled =
        nlohmann::json::parse(ReadText(DataDir() + "/Au-Ag/dataset.json"));
    nlohmann::json manifest = bundled;
    manifest["name"] = kDatasetName;
    ASSERT_EQ(bundled["samples"].size(), kSampleFiles.size());
    for (std::size_t i = 0; i < kSampleFiles.size(); ++i) {
      const fs::path target = fs::path(*folder_) / kSampleFiles[i];
      fs::create_directories(target.parent_path());
      fs::copy_file(DataDir() + "/Au-Ag/" + bundled["samples"][i]["file"].get<std::string>(),
                    target);
      manifest["samples"][i]["file"] = kSampleFiles[i];
    }
    WriteText(*folder_ + "/dataset.json", manifest.dump(2));
  }
  static void TearDownTestSuite() {
    fs::remove_all(*root_);
    delete root_;
    delete folder_;
  }
  static bool HaveChromium() { return fs::exists(kChromium); }

  static std::string* root_;
  static std::string* folder_;
};
std::string* HostileNames::root_ = nullptr;
std::string* HostileNames::folder_ = nullptr;

TEST_F(HostileNames, ExplorerPageFromTheDataSetShowsThemOnlyAsText) {
  const std::string page = *root_ + "/data-explorer.html";
  const RunResult r = RunProgram({"explore", "--data", *folder_, "--method", "paper", "--size",
                                  "64", "--out", page, "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string html = ReadText(page);
  ExpectNoRaw(kRawMarkup, html, "page");
  ExpectNoRaw(kRawInScript, html, "page");
  ExpectOnlyOwnElements(html, 4, "page");
  EXPECT_EQ(Count(Lower(html), "</script"), 4);
  EXPECT_NE(html.find("\\u003cimg src=x onerror=alert(2)\\u003e.yml"), std::string::npos);
  EXPECT_NE(html.find("line\\u2028sep\\u2029.yml"), std::string::npos);
  // The block reads back as the names.
  const nlohmann::json data = nlohmann::json::parse(DataBlock(html));
  ASSERT_EQ(data["training"].size(), kSampleFiles.size());
  for (std::size_t i = 0; i < kSampleFiles.size(); ++i) {
    EXPECT_EQ(data["training"][i]["file"], kSampleFiles[i]);
  }
  EXPECT_NE(data["source"].get<std::string>().find(kFolder), std::string::npos);

  if (!HaveChromium()) GTEST_SKIP() << kChromium << " is absent (Debian package chromium)";
  const std::string dom = DumpDom(*root_, page);
  ASSERT_NE(dom.find("data-ready=\"true\""), std::string::npos)
      << ReadText(*root_ + "/chromium.log");
  ExpectOnlyOwnElements(dom, 4, "DOM");
  // As text: the sample labels (plot titles), the source line and the data set note.
  EXPECT_NE(dom.find("&lt;img src=x onerror=alert(2)&gt;.yml)"), std::string::npos);
  EXPECT_NE(dom.find("x&lt;/script&gt;&lt;script&gt;alert(3)&lt;/script&gt;.yml"),
            std::string::npos);
  EXPECT_NE(dom.find("&lt;svg onload=alert(4)&gt;.yml"), std::string::npos);
  EXPECT_NE(dom.find("&lt;img src=x onerror=alert(1)&gt; \"dq\" 'sq' &amp; amp, paper fit"),
            std::string::npos);
}

TEST_F(HostileNames, ExplorerPageFromAModelShowsItsSourcesOnlyAsText) {
  const std::string model = *folder_ + "/model <b>.json";
  RunResult r =
      RunProgram({"fit", "--data", *folder_, "--method", "paper", "--out", model, "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  nlohmann::json doc = nlohmann::json::parse(ReadText(model));
  ASSERT_TRUE(doc["parameters"]["samples"].is_array());
  for (auto& s : doc["parameters"]["samples"]) s["source"] = kModelSource;
  WriteText(model, doc.dump());
  const std::string page = *root_ + "/model-explorer.html";
  r = RunProgram(
      {"explore", "--model", model, "--size", "64", "--roughness", "0", "--out", page, "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string html = ReadText(page);
  ExpectNoRaw(kRawMarkup, html, "page");
  ExpectNoRaw(kRawInScript, html, "page");
  ExpectOnlyOwnElements(html, 4, "page");
  EXPECT_EQ(Count(Lower(html), "</script"), 4);
  EXPECT_EQ(html.find("model <b>"), std::string::npos);
  EXPECT_NE(html.find("\\u003cimg src=x onerror=alert(7)\\u003e\\u003c/script\\u003e"),
            std::string::npos);

  if (!HaveChromium()) GTEST_SKIP() << kChromium << " is absent (Debian package chromium)";
  const std::string dom = DumpDom(*root_, page);
  ASSERT_NE(dom.find("data-ready=\"true\""), std::string::npos)
      << ReadText(*root_ + "/chromium.log");
  ExpectOnlyOwnElements(dom, 4, "DOM");
  EXPECT_NE(dom.find("(&lt;img src=x onerror=alert(7)&gt;&lt;/script&gt;&lt;script&gt;alert(8)"
                     "&lt;/script&gt;)"),
            std::string::npos);
  EXPECT_NE(dom.find("model &lt;b&gt;.json"), std::string::npos);
}

// A folder name that is not UTF-8 (a byte 0xFF) is shown with U+FFFD, not refused.
TEST_F(HostileNames, ExplorerPageTakesAFolderNameThatIsNotUtf8) {
  const std::string folder = *root_ + "/Au-Ag \xFF";
  fs::copy(DataDir() + "/Au-Ag", folder);
  const std::string page = *root_ + "/not-utf8.html";
  const RunResult r = RunProgram(
      {"explore", "--data", folder, "--method", "paper", "--size", "64", "--out", page, "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json data = nlohmann::json::parse(DataBlock(ReadText(page)));
  EXPECT_NE(data["source"].get<std::string>().find("Au-Ag \xEF\xBF\xBD"), std::string::npos);
}

TEST_F(HostileNames, ValidationReportShowsThemOnlyAsText) {
  const std::string out = *root_ + "/report";
  const RunResult r = RunProgram({"validate", "--data", *folder_, "--methods", "paper,eps-linear",
                                  "--holdout", "0.1,0.2,0.3,0.5", "--out", out, "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string html = ReadText(out + "/report.html");
  ASSERT_FALSE(html.empty());
  ExpectNoRaw(kRawMarkup, html, "report");
  ExpectOnlyOwnElements(html, 0, "report");
  for (const std::string& escaped :
       {std::string("&lt;/script&gt;&lt;b id=hostile-name onclick=alert(6)&gt;name&lt;/b&gt;"),
        std::string("&lt;img src=x onerror=alert(1)&gt; &quot;dq&quot; &#39;sq&#39; &amp; amp"),
        std::string("x&lt;/script&gt;&lt;script&gt;alert(3)&lt;/script&gt;.yml"),
        std::string("&lt;svg onload=alert(4)&gt;.yml"),
        std::string("&quot;dq&quot; &amp; &#39;sq&#39; &lt;!-- c --&gt;.yml")}) {
    EXPECT_NE(html.find(escaped), std::string::npos) << escaped;
  }

  if (!HaveChromium()) GTEST_SKIP() << kChromium << " is absent (Debian package chromium)";
  const std::string dom = DumpDom(*root_, out + "/report.html");
  ASSERT_NE(dom.find("</body>"), std::string::npos) << ReadText(*root_ + "/chromium.log");
  ExpectOnlyOwnElements(dom, 0, "DOM");
  EXPECT_NE(dom.find("&lt;/script&gt;&lt;b id=hostile-name onclick=alert(6)&gt;name&lt;/b&gt;"),
            std::string::npos);
}

}  // namespace
}  // namespace alloycolor
