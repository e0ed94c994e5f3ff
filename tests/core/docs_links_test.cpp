// The project's Markdown documents link to files that exist: every relative link `[text](path)` or
// `[text](path#anchor)` in README.md, docs/, lessons/, bench/, scenes/, viz/ and tests/ resolves from the
// document's own folder (web links and in-page anchors are not followed). A moved document breaks this test,
// not its readers.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

const fs::path kSource = RAYSTEP_SOURCE_DIR;

std::vector<fs::path> documents() {
  std::vector<fs::path> out = {kSource / "README.md"};
  for (const char* dir : {"docs", "lessons", "bench", "scenes", "viz", "tests", "core", "cli"}) {
    if (!fs::is_directory(kSource / dir)) continue;
    for (const auto& e : fs::recursive_directory_iterator(kSource / dir))
      if (e.is_regular_file() && e.path().extension() == ".md") out.push_back(e.path());
  }
  return out;
}

TEST(DocsLinks, EveryRelativeLinkResolves) {
  const std::regex link(R"(\]\(([^)\s]+)\))");
  int checked = 0;
  const std::vector<fs::path> docs = documents();
  ASSERT_GT(docs.size(), 10u);
  for (const fs::path& doc : docs) {
    std::ifstream in(doc);
    std::string line;
    int number = 0;
    bool fenced = false;
    while (std::getline(in, line)) {
      ++number;
      if (line.rfind("```", 0) == 0) fenced = !fenced;
      if (fenced) continue;
      for (std::sregex_iterator it(line.begin(), line.end(), link), end; it != end; ++it) {
        std::string target = (*it)[1];
        if (target.rfind("http://", 0) == 0 || target.rfind("https://", 0) == 0 ||
            target.rfind("mailto:", 0) == 0 || target[0] == '#')
          continue;
        target = target.substr(0, target.find('#'));
        ++checked;
        EXPECT_TRUE(fs::exists(doc.parent_path() / target))
            << fs::relative(doc, kSource).string() << ":" << number << ": no " << target;
      }
    }
  }
  EXPECT_GT(checked, 20);
}

// The documents speak of features, not of the project's issue tracker ("issue 16").
TEST(DocsLinks, NoDocumentNamesAnIssue) {
  const std::regex issue(R"(\b[Ii]ssues? #?[0-9]+)");
  for (const fs::path& doc : documents()) {
    const std::string rel = fs::relative(doc, kSource).string();
    if (rel.rfind("tests/", 0) == 0) continue;  // the tests' notes may say where a case came from
    std::ifstream in(doc);
    std::string line;
    for (int number = 1; std::getline(in, line); ++number)
      EXPECT_FALSE(std::regex_search(line, issue)) << rel << ":" << number << ": " << line;
  }
}

// The front page stays a front page: what raystep is, the commands, a tour and where to read on.
TEST(DocsLinks, ReadmeIsShort) {
  std::ifstream in(kSource / "README.md");
  int lines = 0;
  for (std::string line; std::getline(in, line);) ++lines;
  EXPECT_LE(lines, 250);
}

}  // namespace
