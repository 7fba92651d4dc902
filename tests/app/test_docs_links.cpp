// Every page a page or a message names exists, and every page of docs/ is in the index.
// Checked: `docs/….md` anywhere in the README, the docs and the sources users read messages
// from, and every relative Markdown link `](x.md)`, `](x.md#part)`, `](x.png)` in the README and
// docs/ (resolved against the linking page's directory). Links with a scheme (https://…) are
// not followed.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "tests/support/cli.hpp"

namespace shudder {
namespace {

namespace fs = std::filesystem;

// The relative link targets of a Markdown text, without their #part.
std::vector<std::string> relative_links(const std::string& text) {
  static const std::regex link(R"(\]\(([^)\s#:]+)(#[^)\s]*)?\))");
  std::vector<std::string> out;
  for (std::sregex_iterator it(text.begin(), text.end(), link), end; it != end; ++it) out.push_back((*it)[1].str());
  return out;
}

struct LinkCheck {
  std::vector<std::string> broken;  // "file: target"
  int checked = 0;
};

// `root` is the repository root that `docs/….md` names are resolved against.
LinkCheck check_links(const std::vector<fs::path>& files, const fs::path& root) {
  static const std::regex named(R"(docs/[A-Za-z0-9_/-]+\.md)");
  LinkCheck r;
  for (const auto& f : files) {
    const std::string text = test::slurp(f);
    for (std::sregex_iterator it(text.begin(), text.end(), named), end; it != end; ++it, ++r.checked) {
      if (!fs::exists(root / it->str())) r.broken.push_back(f.string() + ": " + it->str());
    }
    if (f.extension() != ".md") continue;
    for (const auto& target : relative_links(text)) {
      ++r.checked;
      if (!fs::exists(f.parent_path() / target)) r.broken.push_back(f.string() + ": " + target);
    }
  }
  return r;
}

std::vector<fs::path> files_users_read() {
  std::vector<fs::path> files = {test::source_path("README.md")};
  const std::set<std::string> kinds = {".md", ".cpp", ".hpp", ".toml", ".py"};
  for (const char* dir : {"docs", "app", "io", "report", "python", "scenarios", "tools"}) {
    for (const auto& e : fs::recursive_directory_iterator(test::source_path(dir))) {
      if (e.is_regular_file() && kinds.count(e.path().extension().string())) files.push_back(e.path());
    }
  }
  return files;
}

TEST(DocsLinks, EveryNamedOrLinkedPageExists) {
  const auto r = check_links(files_users_read(), test::source_path(""));
  for (const auto& b : r.broken) ADD_FAILURE() << "broken link: " << b;
  EXPECT_GT(r.checked, 100);
}

// The check itself: a page with broken links of every form is caught, its good links are not.
TEST(DocsLinks, ABrokenLinkIsReported) {
  const auto dir = test::scratch_dir("docs_links_broken");
  fs::create_directories(dir / "docs" / "formats");
  std::ofstream(dir / "docs" / "good.md") << "# good\n";
  std::ofstream(dir / "docs" / "formats" / "f.md") << "# f\n";
  std::ofstream(dir / "docs" / "page.md")
      << "See [good](good.md), [part](good.md#a-part), [f](formats/f.md),\n"
         "[up](../docs/good.md), docs/good.md and [web](https://example.org/x.md).\n"
         "Broken: [one](missing.md), [two](missing.md#part), [three](formats/nope.md),\n"
         "[img](gone.png) and docs/not_there.md.\n";
  const auto r = check_links({dir / "docs" / "page.md"}, dir);
  const std::set<std::string> broken(r.broken.begin(), r.broken.end());
  const std::string page = (dir / "docs" / "page.md").string();
  EXPECT_EQ(broken, (std::set<std::string>{page + ": missing.md", page + ": formats/nope.md", page + ": gone.png",
                                           page + ": docs/not_there.md"}));
  EXPECT_EQ(r.broken.size(), 5u);  // missing.md twice
  EXPECT_EQ(r.checked, 11);
}

// The index sorts every page: each Markdown page under docs/ is linked from docs/README.md.
TEST(DocsLinks, EveryPageIsInTheIndex) {
  const fs::path docs = test::source_path("docs");
  std::set<fs::path> linked;
  for (const auto& target : relative_links(test::slurp(docs / "README.md")))
    linked.insert(fs::weakly_canonical(docs / target));
  for (const auto& e : fs::recursive_directory_iterator(docs)) {
    if (e.path().extension() != ".md" || e.path() == docs / "README.md") continue;
    EXPECT_TRUE(linked.count(fs::weakly_canonical(e.path())))
        << fs::relative(e.path(), docs).string() << " is not in docs/README.md";
  }
}

}  // namespace
}  // namespace shudder
