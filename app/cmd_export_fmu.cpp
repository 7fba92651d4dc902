// `shudder export-fmu SCENARIO.toml -o NAME.fmu` (docs/fmu.md "Your drivetrain as an FMU"): a
// network scenario packed as an FMI 2.0 co-simulation FMU (fmu/network_fmu_package.hpp) around
// the network FMU library the build made (fmu/network_fmu.cpp): its linux64 .so and, when the
// build cross-compiled it (MinGW-w64), its win64 .dll, found beside the .so as ../win64/.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <unistd.h>

#include "app/commands.hpp"
#include "app/guarded.hpp"
#include "io/input_error.hpp"
#include "fmu/network_fmu_package.hpp"
#include "io/network_scenario.hpp"
#include "io/output_safety.hpp"

namespace shudder::app {

namespace {

namespace fs = std::filesystem;

// The network FMU library: SHUDDER_NETWORK_FMU_LIBRARY if set, else the build tree's (the
// path this executable was built with), else the installed one beside bin/.
std::string network_fmu_library() {
  if (const char* env = std::getenv("SHUDDER_NETWORK_FMU_LIBRARY"); env && *env) {
    if (!fs::is_regular_file(env))
      throw io::InputError("SHUDDER_NETWORK_FMU_LIBRARY", 0, "",
                           std::string("'") + env + "' is not a file; point it at shudder_network.so or unset it");
    return env;
  }
  std::vector<fs::path> candidates;
#ifdef SHUDDER_NETWORK_FMU_BUILD_LIBRARY
  candidates.emplace_back(SHUDDER_NETWORK_FMU_BUILD_LIBRARY);
#endif
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) candidates.push_back(exe.parent_path().parent_path() / "share/shudder/fmu/linux64/shudder_network.so");
  for (const auto& c : candidates)
    if (fs::is_regular_file(c, ec)) return c.string();
  throw std::runtime_error(
      "the network FMU library shudder_network.so was not found (build it: cmake -DSHUDDER_FMU=ON, "
      "target shudder_network_fmu; or set SHUDDER_NETWORK_FMU_LIBRARY)");
}

// The win64 DLL beside the linux64 library: LINUX64/../win64/shudder_network.dll, as the build
// tree's stage and the installed share/shudder/fmu/ lay them out; "" when there is none.
std::string network_fmu_dll(const std::string& linux64) {
  const fs::path dll = fs::path(linux64).parent_path().parent_path() / "win64/shudder_network.dll";
  std::error_code ec;
  return fs::is_regular_file(dll, ec) ? dll.string() : std::string();
}

}  // namespace

int export_fmu_command(const ExportFmuOptions& opt) {
  return guarded(opt.scenario, "export-fmu", [&]() -> int {
    const std::string type = io::scenario_type(opt.scenario);
    if (type != "network")
      throw io::InputError(opt.scenario, 0, "scenario.type",
                           "export-fmu packs network scenarios (type = \"network\", docs/formats/network_file.md), "
                           "this one is \"" +
                               type + "\"; for the clutch alone use build/fmu/shudder_clutch.fmu");
    io::NetworkScenario sc = io::load_network_scenario(opt.scenario);
    for (const auto& w : sc.warnings) std::cerr << "shudder: warning: " << w << "\n";
    const bool wet = std::any_of(sc.spec.clutches.begin(), sc.spec.clutches.end(),
                                 [](const auto& c) { return c.law != components::ClutchSpec::Law::kPlain; });
    RunOptions as_run;
    as_run.scenario = opt.scenario;
    as_run.fixed_step_s = opt.fixed_step_s;
    require_whole_steps(as_run, sc.spec.settings, wet);
    const std::string out = opt.output.empty() ? sc.name + ".fmu" : opt.output;
    std::vector<io::RolePath> inputs{{"scenario", opt.scenario}};
    for (const auto& f : sc.fluid_paths) inputs.push_back({"fluid file", f});
    io::require_distinct_paths(inputs, {{"-o", out}});
    io::require_output_directory(out);
    fmu::NetworkFmuLibraries libraries;
    libraries.linux64 = network_fmu_library();
    libraries.win64 = network_fmu_dll(libraries.linux64);
    const fmu::NetworkFmuSummary s = fmu::write_network_fmu(sc, opt.fixed_step_s, libraries, out);
    std::cout << "Wrote " << out << ": FMI 2.0 co-simulation, " << s.inputs << " inputs, " << s.outputs << " outputs, "
              << s.parameters << " parameter (fixed_step_s = " << opt.fixed_step_s << " s), GUID " << s.guid << "\n"
              << "Platforms:";
    for (std::size_t i = 0; i < s.platforms.size(); ++i) std::cout << (i ? ", " : " ") << s.platforms[i];
    if (libraries.win64.empty())
      std::cout << " (no win64 DLL beside " << libraries.linux64
                << ": the build makes it when MinGW-w64 is installed, docs/fmu.md \"Platforms\")";
    std::cout << "\n";
    return 0;
  });
}

}  // namespace shudder::app
