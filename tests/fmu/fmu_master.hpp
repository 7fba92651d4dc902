#pragma once
// A co-simulation master's pieces shared by the FMU tests (tests/fmu/test_fmu.cpp for the wet
// clutch, tests/fmu/test_network_fmu.cpp for a network): the logger callback that keeps every
// message, the fmi2* functions of a library looked up by name as an importing tool does, a
// command's output, the check that a linux64 library loads on an old glibc, the check of a
// win64 DLL's export and import tables, and the command line that runs a Windows program
// under Wine.
#include <dlfcn.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdarg>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "fmu/fmi2.h"

namespace shudder::fmu_test {

namespace fs = std::filesystem;

inline std::vector<std::string> g_log;
inline void logger(fmi2ComponentEnvironment, fmi2String, fmi2Status status, fmi2String category, fmi2String message,
                   ...) {
  char text[1024];
  va_list args;
  va_start(args, message);
  std::vsnprintf(text, sizeof text, message, args);
  va_end(args);
  g_log.push_back(std::string(category) + " [" + std::to_string(status) + "] " + text);
}
inline bool logged(const std::string& part) {
  for (const auto& l : g_log)
    if (l.find(part) != std::string::npos) return true;
  return false;
}

// The FMU's functions, looked up by name as an importing tool does.
struct Fmu {
  explicit Fmu(fs::path lib) : library(std::move(lib)) {}
  fs::path library;  // declared first: the lookups below run in the member initialisers
  void* handle = nullptr;
#define FMI2_FN(name) decltype(&::name) name = reinterpret_cast<decltype(&::name)>(lookup(#name))
  void* lookup(const char* name) {
    if (!handle) handle = dlopen(library.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) throw std::runtime_error(std::string("dlopen: ") + dlerror());
    void* f = dlsym(handle, name);
    if (!f) throw std::runtime_error(std::string("missing ") + name);
    return f;
  }
  FMI2_FN(fmi2GetVersion);
  FMI2_FN(fmi2GetTypesPlatform);
  FMI2_FN(fmi2Instantiate);
  FMI2_FN(fmi2FreeInstance);
  FMI2_FN(fmi2SetupExperiment);
  FMI2_FN(fmi2EnterInitializationMode);
  FMI2_FN(fmi2ExitInitializationMode);
  FMI2_FN(fmi2Terminate);
  FMI2_FN(fmi2Reset);
  FMI2_FN(fmi2GetReal);
  FMI2_FN(fmi2SetReal);
  FMI2_FN(fmi2SetInteger);
  FMI2_FN(fmi2SetBoolean);
  FMI2_FN(fmi2SetString);
  FMI2_FN(fmi2GetString);
  FMI2_FN(fmi2DoStep);
  FMI2_FN(fmi2GetRealStatus);
  FMI2_FN(fmi2GetStatus);
  FMI2_FN(fmi2GetIntegerStatus);
  FMI2_FN(fmi2GetBooleanStatus);
  FMI2_FN(fmi2GetStringStatus);
  FMI2_FN(fmi2SetDebugLogging);
#undef FMI2_FN
};

inline std::string command_output(const std::string& cmd) {
  std::string out;
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(cmd.c_str(), "r"), pclose);
  if (!pipe) return out;
  std::array<char, 512> buf{};
  while (fgets(buf.data(), buf.size(), pipe.get())) out += buf.data();
  return out;
}

inline  // "2.17" < "2.34": version numbers compared field by field.
    bool
    version_above(const std::string& a, const std::string& b) {
  std::vector<int> x, y;
  for (const std::string* s : {&a, &b}) {
    auto& v = s == &a ? x : y;
    std::size_t p = 0;
    while (p < s->size()) {
      const std::size_t q = s->find('.', p);
      v.push_back(std::stoi(s->substr(p, q - p)));
      p = q == std::string::npos ? s->size() : q + 1;
    }
  }
  return std::lexicographical_compare(y.begin(), y.end(), x.begin(), x.end());
}

/// The library's dynamic symbol table names no glibc newer than `minimum` (nor GCC_ beyond
/// 4.8.0, nor libstdc++'s versions: linked statically), and it needs only the C runtime's
/// libraries. Stated minimum: docs/fmu.md "Platforms".
inline void expect_loads_on_glibc(const fs::path& library, const std::string& minimum) {
  // The dynamic symbol table names the version of every libc function the library binds; the
  // dynamic loader refuses the library on a glibc that lacks one. Stated minimum: docs/fmu.md.
  EXPECT_TRUE(version_above("2.34", "2.17") && !version_above("2.17", "2.17") && version_above("2.3.2", "2.3"));
  const std::string table = command_output("objdump -T " + library.string());
  ASSERT_NE(table.find("GLIBC_2.2.5"), std::string::npos) << table;
  const std::regex version(R"(\b(GLIBC|GCC|GLIBCXX|CXXABI)_([0-9.]+)\)?\s+(\S+)\s*$)");
  std::set<std::string> newest_ok;
  std::istringstream lines(table);
  for (std::string line; std::getline(lines, line);) {
    std::smatch m;
    if (!std::regex_search(line, m, version)) continue;
    const std::string kind = m[1], number = m[2], symbol = m[3];
    EXPECT_NE(kind, "GLIBCXX") << "libstdc++ is linked statically: " << line;
    EXPECT_NE(kind, "CXXABI") << line;
    if (kind == "GLIBC") {
      EXPECT_FALSE(version_above(number, minimum)) << symbol << " needs GLIBC_" << number;
    }
    // libgcc_s.so.1: GCC 4.8 (the compiler of glibc-2.17 systems) defines up to GCC_4.8.0.
    if (kind == "GCC") {
      EXPECT_FALSE(version_above(number, "4.8.0")) << symbol << " needs GCC_" << number;
    }
  }
  // Only the C runtime's libraries are needed.
  const std::string headers = command_output("objdump -p " + library.string());
  std::istringstream h(headers);
  const std::set<std::string> allowed = {"libc.so.6", "libm.so.6", "libpthread.so.0", "libgcc_s.so.1",
                                         "ld-linux-x86-64.so.2"};
  int needed = 0;
  for (std::string line; std::getline(h, line);) {
    std::istringstream w(line);
    std::string key, lib;
    w >> key >> lib;
    if (key != "NEEDED") continue;
    ++needed;
    EXPECT_TRUE(allowed.count(lib)) << "needs " << lib;
  }
  EXPECT_GE(needed, 2);
}

/// A win64 FMU DLL's export table holds the 34 fmi2 functions and its imports are Windows' own
/// DLLs only (everything else linked statically, docs/fmu.md "Platforms").
inline void expect_win64_dll_exports(const fs::path& dll) {
  const std::string pe = command_output("x86_64-w64-mingw32-objdump -p " + dll.string());
  int exported = 0;
  for (std::size_t at = pe.find("] fmi2"); at != std::string::npos; at = pe.find("] fmi2", at + 1)) ++exported;
  EXPECT_EQ(exported, 34) << dll << "\n" << pe.substr(0, 4000);
  std::regex imported(R"(DLL Name: (\S+))");
  int imports = 0;
  for (auto it = std::sregex_iterator(pe.begin(), pe.end(), imported); it != std::sregex_iterator(); ++it) {
    std::string name = (*it)[1];
    std::transform(name.begin(), name.end(), name.begin(), [](unsigned char ch) { return std::tolower(ch); });
    EXPECT_TRUE(name == "kernel32.dll" || name == "msvcrt.dll" || name.rfind("api-ms-win-", 0) == 0 ||
                name == "user32.dll" || name == "advapi32.dll")
        << dll << " imports " << name;
    ++imports;
  }
  EXPECT_GE(imports, 1) << pe.substr(0, 4000);
}

/// The command line that runs a Windows program under Wine in the build tree's prefix
/// (created on the first run), one Wine at a time (flock: two tests creating the prefix at
/// once would race).
inline std::string wine_command(const std::string& wine, const std::string& prefix, const std::string& args) {
  return "flock " + prefix + ".lock env WINEPREFIX=" + prefix + " WINEDEBUG=-all WINEDLLOVERRIDES='mscoree,mshtml=' " +
         wine + " " + args;
}

/// "name value" lines of a load check's output.
inline std::map<std::string, double> name_values(const std::string& text) {
  std::map<std::string, double> values;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    std::istringstream w(line);
    std::string name;
    double v = 0.0;
    if (w >> name >> v) values[name] = v;
  }
  return values;
}

}  // namespace shudder::fmu_test
