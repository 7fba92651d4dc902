// The folders' one-way arrows (docs/architecture.md) as a test: every `#include "FOLDER/..."`
// in a product source must point to its own folder or one below it. An include against the
// arrows (e.g. analysis/ including rig_models/, io/ including report/) fails here, naming the
// file and line, before it can grow into a cycle.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

// Folder -> the folders it may include (besides itself).
const std::map<std::string, std::set<std::string>>& allowed() {
  static const std::map<std::string, std::set<std::string>> k = {
      {"core", {}},
      {"clutch", {"core"}},
      {"dynamics", {"core"}},
      {"analysis", {"core", "clutch", "dynamics"}},
      {"components", {"core", "clutch", "dynamics"}},                // the elements and the network
      {"rig_models", {"core", "clutch", "dynamics", "components"}},  // the machines: no analysis
      {"studies", {"core", "clutch", "dynamics", "analysis", "rig_models", "components"}},
      {"io", {"core", "clutch", "dynamics", "analysis", "rig_models", "components", "studies"}},
      {"report", {"core", "clutch", "dynamics", "analysis", "rig_models", "components", "studies", "io"}},
      {"app", {"core", "clutch", "dynamics", "analysis", "rig_models", "components", "studies", "io", "report", "fmu"}},
      {"python",
       {"core", "clutch", "dynamics", "analysis", "rig_models", "components", "studies", "io", "report", "app"}},
      {"fmu", {"core", "clutch", "dynamics", "rig_models", "components", "io"}},  // the FMU, beside app: steps only
  };
  return k;
}

TEST(IncludeArrows, EveryIncludePointsDownTheLayers) {
  const fs::path root = SHUDDER_SOURCE_DIR;
  const std::regex include(R"re(^\s*#\s*include\s*"([a-z_]+)/)re");
  std::vector<std::string> violations;
  std::size_t files = 0;
  for (const auto& [folder, may] : allowed()) {
    ASSERT_TRUE(fs::is_directory(root / folder)) << folder;
    for (const auto& entry : fs::directory_iterator(root / folder)) {
      const auto ext = entry.path().extension();
      if (ext != ".hpp" && ext != ".cpp") continue;
      ++files;
      std::ifstream in(entry.path());
      std::string line;
      for (int n = 1; std::getline(in, line); ++n) {
        std::smatch m;
        if (!std::regex_search(line, m, include)) continue;
        const std::string target = m[1];
        if (target != folder && !may.count(target) && allowed().count(target))
          violations.push_back(folder + "/" + entry.path().filename().string() + ":" + std::to_string(n) +
                               " includes " + target + "/");
      }
    }
  }
  EXPECT_GT(files, 100u);  // the scan saw the sources (not an empty or moved tree)
  for (const auto& v : violations) ADD_FAILURE() << v;
}

}  // namespace
