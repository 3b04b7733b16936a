// The repository stands on its own: every relative file link in README.md and docs/*.md points
// at a file of the repository, and no file cites notes that live outside it.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "support/file_text.hpp"
#include "support/test_paths.hpp"

namespace {

namespace fs = std::filesystem;

const fs::path kRoot = LAGRANGE_SOURCE_DIR;

std::vector<fs::path> markdown_pages() {
  std::vector<fs::path> pages{kRoot / "README.md"};
  for (const auto& e : fs::directory_iterator(kRoot / "docs"))
    if (e.path().extension() == ".md") pages.push_back(e.path());
  return pages;
}

// Build trees (a CMakeCache.txt), git's store and the demo's output are not the repository.
bool outside_repository(const fs::path& dir) {
  const std::string name = dir.filename().string();
  return name == ".git" || name == "out" || fs::exists(dir / "CMakeCache.txt");
}

TEST(Docs, PagesExist) {
  EXPECT_TRUE(fs::exists(kRoot / "docs" / "theory.md"));
  EXPECT_TRUE(fs::exists(kRoot / "docs" / "benchmarks.md"));
  EXPECT_GE(markdown_pages().size(), 5u);
}

// [text](target) and ![alt](target): targets that are not web addresses or in-page anchors
// must name an existing file or directory, relative to the page.
TEST(Docs, RelativeLinksResolve) {
  const std::regex link(R"(\]\(([^)\s]+)\))");
  size_t checked = 0;
  for (const fs::path& page : markdown_pages()) {
    const std::string text = lagrange::test::slurp(page);
    for (auto it = std::sregex_iterator(text.begin(), text.end(), link);
         it != std::sregex_iterator(); ++it) {
      std::string target = (*it)[1].str();
      if (target.rfind("http://", 0) == 0 || target.rfind("https://", 0) == 0 ||
          target.rfind("mailto:", 0) == 0 || target[0] == '#')
        continue;
      target = target.substr(0, target.find('#'));
      EXPECT_TRUE(fs::exists(page.parent_path() / target))
          << page.lexically_relative(kRoot).string() << " links to '" << target
          << "', which is not in the repository";
      ++checked;
    }
  }
  EXPECT_GE(checked, 5u) << "no links found: the link pattern no longer matches the pages";
}

// The design notes, the peer notes and the folder beside the repository are not shipped: no
// file may send a reader there (cite docs/theory.md and docs/benchmarks.md instead). The names
// are assembled so that this file does not match itself.
TEST(Docs, NoCitationOutsideTheRepository) {
  const std::vector<std::string> forbidden{
      std::string("DESIGN") + ".md", std::string("PEERS") + ".md", std::string("..") + "/shared"};
  size_t files = 0;
  for (auto it = fs::recursive_directory_iterator(kRoot); it != fs::recursive_directory_iterator();
       ++it) {
    if (it->is_directory()) {
      if (outside_repository(it->path())) it.disable_recursion_pending();
      continue;
    }
    if (!it->is_regular_file()) continue;
    ++files;
    const std::string text = lagrange::test::slurp(it->path());
    for (const auto& name : forbidden)
      EXPECT_EQ(text.find(name), std::string::npos)
          << it->path().lexically_relative(kRoot).string() << " mentions " << name;
  }
  EXPECT_GE(files, 50u);
}

}  // namespace
