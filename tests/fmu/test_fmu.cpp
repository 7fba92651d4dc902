// A co-simulation master in miniature for the wet-clutch FMU (docs/fmu.md): dlopens the built
// shared library and follows FMI 2.0's calling sequence (instantiate, set up, initialise, step,
// terminate, reset, free), its error paths, and checks the packed modelDescription.xml against
// the variable table the library serves.
#include <dlfcn.h>
#include <expat.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "fmu/fmi2.h"
#include "fmu/variables.hpp"
#include "io/hdf5_run.hpp"
#include "rig_models/drive_cycle.hpp"

namespace shudder {
namespace {

namespace fs = std::filesystem;
namespace vr = fmu::vr;

const fs::path kStage = SHUDDER_FMU_STAGE;
const fs::path kLibrary = kStage / "binaries/linux64/shudder_clutch.so";
const std::string kFluid = std::string(SHUDDER_SOURCE_DIR) + "/scenarios/fluids/lsc_fluid_c.toml";

std::vector<std::string> g_log;
void logger(fmi2ComponentEnvironment, fmi2String, fmi2Status status, fmi2String category, fmi2String message, ...) {
  char text[1024];
  va_list args;
  va_start(args, message);
  std::vsnprintf(text, sizeof text, message, args);
  va_end(args);
  g_log.push_back(std::string(category) + " [" + std::to_string(status) + "] " + text);
}
bool logged(const std::string& part) {
  for (const auto& l : g_log)
    if (l.find(part) != std::string::npos) return true;
  return false;
}

// The FMU's functions, looked up by name as an importing tool does.
struct Fmu {
  void* handle = nullptr;
#define FMI2_FN(name) decltype(&::name) name = reinterpret_cast<decltype(&::name)>(lookup(#name))
  void* lookup(const char* name) {
    if (!handle) handle = dlopen(kLibrary.c_str(), RTLD_NOW | RTLD_LOCAL);
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
#undef FMI2_FN
};

Fmu& fmu_functions() {
  static Fmu f;
  return f;
}

const fmi2CallbackFunctions kCallbacks = {logger, nullptr, nullptr, nullptr, nullptr};
const std::string kResources = "file://" + (kStage / "resources").string();

fmi2Component instantiate(Fmu& f) {
  return f.fmi2Instantiate("clutch", fmi2CoSimulation, std::string(fmu::kGuid).c_str(), kResources.c_str(),
                           &kCallbacks, fmi2False, fmi2False);
}

double get(Fmu& f, fmi2Component c, unsigned ref) {
  double v = NAN;
  EXPECT_EQ(f.fmi2GetReal(c, &ref, 1, &v), fmi2OK);
  return v;
}
void set(Fmu& f, fmi2Component c, unsigned ref, double v) { EXPECT_EQ(f.fmi2SetReal(c, &ref, 1, &v), fmi2OK); }

// A prescribed-slip scenario and the same inputs for the FMU: slip and force vary, two
// interfaces, 60 °C start, viscous shear on (parameters away from the defaults).
const rig_models::PiecewiseLinear kSlipRpm({0.0, 0.4, 1.0, 1.5}, {5.0, 60.0, 30.0, 80.0});
const rig_models::PiecewiseLinear kForceN({0.0, 0.4, 1.0, 1.5}, {8000.0, 20000.0, 15000.0, 25000.0});
constexpr double kDuration = 1.5, kStep = 1e-4;

std::string scenario_text() {
  return "[scenario]\nname = \"fmu_check\"\ntype = \"prescribed_slip\"\nduration_s = 1.5\n"
         "[clutch]\nfluid = \"" + kFluid + "\"\nstart_temp_C = 60.0\nsliding_interfaces = 2\n"
         "[effects.viscous_shear]\nenabled = true\n"
         "[drive]\ntime_s = [0.0, 0.4, 1.0, 1.5]\nspeed_rpm = [5.0, 60.0, 30.0, 80.0]\n"
         "normal_force_N = [8000.0, 20000.0, 15000.0, 25000.0]\n"
         "[output]\nsample_rate_Hz = 100.0\n";
}

void configure(Fmu& f, fmi2Component c) {
  set(f, c, vr::kStartTemp, 60.0);
  set(f, c, vr::kSumpStartTemp, 60.0);
  const unsigned n_ref = vr::kSlidingInterfaces;
  const fmi2Integer two = 2;
  EXPECT_EQ(f.fmi2SetInteger(c, &n_ref, 1, &two), fmi2OK);
  const unsigned visc = vr::kViscousShear;
  const fmi2Boolean on = fmi2True;
  EXPECT_EQ(f.fmi2SetBoolean(c, &visc, 1, &on), fmi2OK);
  const unsigned fluid = vr::kFluidFile;
  const fmi2String path = kFluid.c_str();
  EXPECT_EQ(f.fmi2SetString(c, &fluid, 1, &path), fmi2OK);
}

// Sets the inputs at t (the slip split over two shafts) and steps to t + h.
void step(Fmu& f, fmi2Component c, double t) {
  const double slip = kSlipRpm(t) * 2.0 * M_PI / 60.0;
  set(f, c, vr::kSpeedA, slip + 10.0);
  set(f, c, vr::kSpeedB, 10.0);
  set(f, c, vr::kClampForce, kForceN(t));
  ASSERT_EQ(f.fmi2DoStep(c, t, kStep, fmi2True), fmi2OK);
}

TEST(Fmu, OutputsEqualShudderRunFixedStepOnTheSameInputs) {
  // The reference: the CLI's fixed-step run of the same scenario (the same RealtimeCoupling,
  // step and thermal handover; inputs held over each step as the FMU holds them). What can
  // differ is round-off: the FMU receives the slip as (slip + 10) − 10 rad/s, a relative
  // change of ~1e-15 in the torque; 1e-6 is the bound, far above it.
  const fs::path dir = fs::temp_directory_path() / "shudder_fmu_test";
  fs::create_directories(dir);
  { std::ofstream(dir / "fmu_check.toml") << scenario_text(); }
  const std::string cmd = std::string(SHUDDER_CLI) + " run " + (dir / "fmu_check.toml").string() + " -o " +
                          (dir / "run.h5").string() + " --fixed-step 1e-4 > /dev/null";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  const dynamics::Recording run = io::read_run_hdf5((dir / "run.h5").string());

  Fmu& f = fmu_functions();
  EXPECT_STREQ(f.fmi2GetVersion(), "2.0");
  EXPECT_STREQ(f.fmi2GetTypesPlatform(), "default");
  fmi2Component c = instantiate(f);
  ASSERT_NE(c, nullptr);
  configure(f, c);
  ASSERT_EQ(f.fmi2SetupExperiment(c, fmi2False, 0.0, 0.0, fmi2True, kDuration), fmi2OK);
  ASSERT_EQ(f.fmi2EnterInitializationMode(c), fmi2OK);
  ASSERT_EQ(f.fmi2ExitInitializationMode(c), fmi2OK);

  const auto& t_run = run.find("time_s")->values;
  const std::map<unsigned, std::string> compared = {
      {vr::kTorque, "torque_Nm"}, {vr::kClutchTorque, "clutch_torque_Nm"}, {vr::kHeat, "heat_power_W"},
      {vr::kThermocouple, "temp_C"}, {vr::kIr, "ir_temp_C"}, {vr::kSump, "sump_temp_C"},
      {vr::kInterfaceMean, "interface_mean_temp_C"}, {vr::kInterfaceMax, "interface_max_temp_C"}};
  const long n = std::lround(kDuration / kStep);
  std::size_t checked = 0;
  for (long k = 0; k < n; ++k) {
    step(f, c, static_cast<double>(k) * kStep);
    if ((k + 1) % 100 != 0) continue;
    const std::size_t j = static_cast<std::size_t>((k + 1) / 100);
    ASSERT_NEAR(t_run[j], (k + 1) * kStep, 1e-12);
    for (const auto& [ref, name] : compared) {
      const double a = get(f, c, ref), b = run.find(name)->values[j];
      ASSERT_NEAR(a, b, 1e-6 * std::max(1.0, std::abs(b))) << name << " at t = " << t_run[j];
    }
    ++checked;
  }
  EXPECT_EQ(checked, 150u);
  EXPECT_GT(get(f, c, vr::kInterfaceMax), 61.0);  // it heated: the comparison covers the thermal path
  double last = 0.0;
  EXPECT_EQ(f.fmi2GetRealStatus(c, fmi2LastSuccessfulTime, &last), fmi2OK);
  EXPECT_NEAR(last, kDuration, 1e-12);

  // Reset: back to the start values; the same run gives the same outputs.
  const double torque_end = get(f, c, vr::kTorque);
  EXPECT_EQ(f.fmi2Terminate(c), fmi2OK);
  ASSERT_EQ(f.fmi2Reset(c), fmi2OK);
  EXPECT_EQ(get(f, c, vr::kStartTemp), 20.0);
  configure(f, c);
  ASSERT_EQ(f.fmi2SetupExperiment(c, fmi2False, 0.0, 0.0, fmi2False, 0.0), fmi2OK);
  ASSERT_EQ(f.fmi2EnterInitializationMode(c), fmi2OK);
  ASSERT_EQ(f.fmi2ExitInitializationMode(c), fmi2OK);
  for (long k = 0; k < n; ++k) step(f, c, static_cast<double>(k) * kStep);
  EXPECT_EQ(get(f, c, vr::kTorque), torque_end);
  EXPECT_EQ(f.fmi2Terminate(c), fmi2OK);
  f.fmi2FreeInstance(c);
  fs::remove_all(dir);
}

TEST(Fmu, ErrorPathsReturnFmi2ErrorWithALoggedReason) {
  Fmu& f = fmu_functions();
  g_log.clear();
  // A GUID from another FMU: no instance.
  EXPECT_EQ(f.fmi2Instantiate("x", fmi2CoSimulation, "{other}", kResources.c_str(), &kCallbacks, fmi2False, fmi2False),
            nullptr);
  EXPECT_TRUE(logged("GUID does not match"));

  fmi2Component c = instantiate(f);
  ASSERT_NE(c, nullptr);
  // Stepping before initialisation.
  EXPECT_EQ(f.fmi2DoStep(c, 0.0, kStep, fmi2True), fmi2Error);
  EXPECT_TRUE(logged("fmi2DoStep: not allowed before fmi2ExitInitializationMode"));
  // Unknown value references and setting an output.
  const unsigned bad = 999;
  double v = 0.0;
  EXPECT_EQ(f.fmi2GetReal(c, &bad, 1, &v), fmi2Error);
  EXPECT_TRUE(logged("unknown value reference 999"));
  const unsigned string_ref = vr::kFluidFile;  // a String asked as Real
  EXPECT_EQ(f.fmi2GetReal(c, &string_ref, 1, &v), fmi2Error);
  const unsigned out = vr::kTorque;
  EXPECT_EQ(f.fmi2SetReal(c, &out, 1, &v), fmi2Error);
  EXPECT_TRUE(logged("torque_Nm is an output"));
  // A fluid file that does not exist: initialisation fails with the path in the message.
  const unsigned fluid = vr::kFluidFile;
  const fmi2String missing = "no/such/fluid.toml";
  ASSERT_EQ(f.fmi2SetString(c, &fluid, 1, &missing), fmi2OK);
  ASSERT_EQ(f.fmi2SetupExperiment(c, fmi2False, 0.0, 0.0, fmi2False, 0.0), fmi2OK);
  ASSERT_EQ(f.fmi2EnterInitializationMode(c), fmi2OK);
  EXPECT_EQ(f.fmi2ExitInitializationMode(c), fmi2Error);
  EXPECT_TRUE(logged("fluid_file: '" + (kStage / "resources/no/such/fluid.toml").string() + "' is not a readable file"));
  // Reset recovers; the default (bundled) fluid works.
  ASSERT_EQ(f.fmi2Reset(c), fmi2OK);
  ASSERT_EQ(f.fmi2EnterInitializationMode(c), fmi2OK);
  ASSERT_EQ(f.fmi2ExitInitializationMode(c), fmi2OK);
  // Negative, zero and non-multiple steps; a parameter set after initialisation.
  EXPECT_EQ(f.fmi2DoStep(c, 0.0, -kStep, fmi2True), fmi2Error);
  EXPECT_TRUE(logged("communicationStepSize must be > 0"));
  EXPECT_EQ(f.fmi2DoStep(c, 0.0, 0.0, fmi2True), fmi2Error);
  EXPECT_EQ(f.fmi2DoStep(c, 0.0, 1.5e-4, fmi2True), fmi2Error);
  EXPECT_TRUE(logged("whole multiple of fixed_step_s"));
  const unsigned radius = vr::kInnerRadius;
  const double r = 30.0;
  EXPECT_EQ(f.fmi2SetReal(c, &radius, 1, &r), fmi2Error);
  EXPECT_TRUE(logged("parameter inner_radius_mm is fixed"));
  // A communication step of 10 fixed steps is fine, and the time must follow.
  EXPECT_EQ(f.fmi2DoStep(c, 0.0, 1e-3, fmi2True), fmi2OK);
  EXPECT_EQ(f.fmi2DoStep(c, 0.5, 1e-3, fmi2True), fmi2Error);
  EXPECT_TRUE(logged("differs from the FMU's time"));
  f.fmi2FreeInstance(c);
}

// modelDescription.xml, parsed with expat: well-formed, and its variables are the library's.
struct XmlVariable {
  std::string name, causality, variability, type;
  unsigned vr = 0;
  bool has_start = false;
};
struct XmlModel {
  std::map<std::string, std::string> root, cosim;
  std::vector<XmlVariable> variables;
  std::vector<int> outputs;
  std::string section;
};

void on_start(void* data, const XML_Char* name, const XML_Char** attrs) {
  auto& m = *static_cast<XmlModel*>(data);
  std::map<std::string, std::string> a;
  for (int i = 0; attrs[i]; i += 2) a[attrs[i]] = attrs[i + 1];
  const std::string el = name;
  if (el == "fmiModelDescription") m.root = a;
  if (el == "CoSimulation") m.cosim = a;
  if (el == "ScalarVariable")
    m.variables.push_back({a["name"], a["causality"], a["variability"], "", static_cast<unsigned>(std::stoul(a["valueReference"])), false});
  if ((el == "Real" || el == "Integer" || el == "Boolean" || el == "String") && !m.variables.empty() &&
      m.variables.back().type.empty()) {
    m.variables.back().type = el;
    m.variables.back().has_start = a.count("start") > 0;
  }
  if (el == "Outputs" || el == "InitialUnknowns") m.section = el;
  if (el == "Unknown" && m.section == "Outputs") m.outputs.push_back(std::stoi(a["index"]));
}
void on_end(void*, const XML_Char*) {}

TEST(Fmu, ModelDescriptionIsWellFormedAndMatchesTheVariableTable) {
  std::ifstream in(kStage / "modelDescription.xml");
  ASSERT_TRUE(in);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  XmlModel m;
  XML_Parser p = XML_ParserCreate("UTF-8");
  XML_SetUserData(p, &m);
  XML_SetElementHandler(p, on_start, on_end);
  const bool ok = XML_Parse(p, text.data(), static_cast<int>(text.size()), 1) == XML_STATUS_OK;
  EXPECT_TRUE(ok) << XML_ErrorString(XML_GetErrorCode(p)) << " at line " << XML_GetCurrentLineNumber(p);
  XML_ParserFree(p);
  ASSERT_TRUE(ok);

  EXPECT_EQ(m.root["fmiVersion"], "2.0");
  EXPECT_EQ(m.root["guid"], fmu::kGuid);
  EXPECT_EQ(m.cosim["modelIdentifier"], fmu::kModelIdentifier);
  EXPECT_TRUE(fs::exists(kStage / "binaries/linux64" / (std::string(fmu::kModelIdentifier) + ".so")));

  // Every XML variable is in the table with the same name, type and causality, and vice versa.
  const std::map<fmu::Type, std::string> type_name = {
      {fmu::Type::kReal, "Real"}, {fmu::Type::kInteger, "Integer"}, {fmu::Type::kBoolean, "Boolean"},
      {fmu::Type::kString, "String"}};
  const std::map<fmu::Causality, std::string> causality_name = {
      {fmu::Causality::kParameter, "parameter"}, {fmu::Causality::kInput, "input"}, {fmu::Causality::kOutput, "output"}};
  std::set<unsigned> xml_refs, table_refs;
  std::vector<int> output_indices;
  for (std::size_t i = 0; i < m.variables.size(); ++i) {
    const auto& x = m.variables[i];
    EXPECT_TRUE(xml_refs.insert(x.vr).second) << "duplicate valueReference " << x.vr;
    const fmu::Variable* t = nullptr;
    for (const auto& v : fmu::kVariables)
      if (v.vr == x.vr) t = &v;
    ASSERT_NE(t, nullptr) << "valueReference " << x.vr << " (" << x.name << ") is not served by the library";
    EXPECT_EQ(x.name, t->name);
    EXPECT_EQ(x.type, type_name.at(t->type)) << x.name;
    EXPECT_EQ(x.causality, causality_name.at(t->causality)) << x.name;
    // FMI 2.0 table of valid combinations: parameters are fixed or tunable; inputs and outputs
    // continuous only if Real; parameters and inputs carry a start value, calculated outputs none.
    if (x.causality == "parameter") {
      EXPECT_TRUE(x.variability == "fixed" || x.variability == "tunable") << x.name;
    }
    if (x.causality == "input" || x.causality == "output") {
      EXPECT_TRUE(x.variability == "continuous" || x.variability == "discrete") << x.name;
      if (x.variability == "continuous") {
        EXPECT_EQ(x.type, "Real") << x.name;
      }
    }
    EXPECT_EQ(x.has_start, x.causality != "output") << x.name;
    if (x.causality == "output") output_indices.push_back(static_cast<int>(i) + 1);
  }
  for (const auto& v : fmu::kVariables) table_refs.insert(v.vr);
  EXPECT_EQ(xml_refs, table_refs);
  EXPECT_EQ(m.outputs, output_indices);  // ModelStructure lists exactly the outputs, by 1-based index
}

std::string command_output(const std::string& cmd) {
  std::string out;
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(cmd.c_str(), "r"), pclose);
  if (!pipe) return out;
  std::array<char, 512> buf{};
  while (fgets(buf.data(), buf.size(), pipe.get())) out += buf.data();
  return out;
}

TEST(Fmu, ArchiveHoldsTheDescriptionAndTheLibraryWhichExportsOnlyFmi2AndNeedsNoProjectLibraries) {
  const std::string listing =
      command_output(std::string(SHUDDER_CMAKE) + " -E tar tf " + SHUDDER_FMU_FILE + " 2>&1");
  EXPECT_NE(listing.find("modelDescription.xml"), std::string::npos) << listing;
  EXPECT_NE(listing.find("binaries/linux64/shudder_clutch.so"), std::string::npos) << listing;
  EXPECT_NE(listing.find("resources/fluids/lsc_fluid_c.toml"), std::string::npos) << listing;

  const std::string symbols = command_output("nm -D --defined-only " + kLibrary.string());
  ASSERT_FALSE(symbols.empty());
  int fmi2 = 0;
  std::size_t start = 0;
  while (start < symbols.size()) {
    const std::size_t end = symbols.find('\n', start);
    const std::string line = symbols.substr(start, end - start);
    start = end == std::string::npos ? symbols.size() : end + 1;
    if (line.empty()) continue;
    const std::string name = line.substr(line.rfind(' ') + 1);
    EXPECT_EQ(name.rfind("fmi2", 0), 0u) << "exported: " << name;
    ++fmi2;
  }
  EXPECT_EQ(fmi2, 34);  // every FMI 2.0 co-simulation function, nothing else
  const std::string needed = command_output("ldd " + kLibrary.string());
  for (const char* lib : {"libshudder", "libtomlplusplus", "libstdc++", "libhdf5"})
    EXPECT_EQ(needed.find(lib), std::string::npos) << needed;
}

}  // namespace
}  // namespace shudder
