// A co-simulation master for an FMU made by `shudder export-fmu` (docs/fmu.md "Your drivetrain
// as an FMU"): exports a shipped network with a wet clutch, unpacks it, loads its linux64
// library with dlopen and runs it as a master would (instantiate, set up, initialise, step, read
// outputs), against `shudder run --fixed-step 1e-4` of the same scenario.
//
// The scenarios: scenarios/networks/manual_launch_wet_clutch.toml (engine with idle governor,
// wet clutch on a falling mu-v fluid, first gear, driveshaft, tyre, car on a 12 % grade) with
// its clutch's ramp replaced by a constant normal force u = 0.6 and 1 s long, and
// scenarios/networks/haldex_car_low_mu_uphill.toml (AWD car, Haldex coupling whose control unit
// sets the valve every 10 ms from the axle speeds) with its engine torque and pedal held at
// their full values and 0.25 s long; so their signals are constant and the FMU's inputs, held
// at their start values (the signals at t = 0), are the scenario's signals exactly. The Haldex
// FMU runs to 0.5 s, past its scenario's duration, against a run of the same scenario 0.5 s
// long: the control unit's instants go on on the FMU's clock.
//
// Why the comparisons hold to round-off: the FMU steps the same right-hand side with the same
// RK4 step and the same thermal-step instants (components/network_stepper.hpp). With
// communication steps of one thermal step (10 ms) the integrator's calls are the run's own, so
// the outputs are the run's values; with 1 ms steps each thermal step is advanced in ten pieces
// whose step lengths differ from the run's by an ulp, a relative 1e-16 per step that the
// dynamics carry over 10^4 steps. The tolerances below are the figures measured on this
// scenario with a margin (docs/fmu.md).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "fmu/content_guid.hpp"
#include "fmu/network_variables.hpp"
#include "io/hdf5_run.hpp"
#include "io/zip_archive.hpp"
#include "tests/fmu/fmu_master.hpp"

namespace shudder {
namespace {

namespace fs = std::filesystem;
using namespace fmu_test;

// Each test process works in a folder of its own (ctest runs the tests as processes in
// parallel, and each exports afresh), removed when the process ends.
const fs::path kWork = fs::temp_directory_path() / ("shudder_network_fmu_test." + std::to_string(getpid()));
struct RemovedAtExit {
  ~RemovedAtExit() {
    std::error_code ec;
    fs::remove_all(kWork, ec);
  }
} removed_at_exit;

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

int run_cli(const std::string& args, std::string* err = nullptr) {
  const fs::path err_file = kWork / "stderr.txt";
  const std::string cmd = std::string(SHUDDER_CLI) + " " + args + " > /dev/null 2> " + err_file.string();
  const int rc = std::system(cmd.c_str());
  if (err) *err = read_text(err_file);
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

// A shipped network with its signals held (header) in kWork/networks/NAME.toml, its fluid in
// kWork/fluids/ where its "../fluids/" path finds it: each (pattern, replacement) applied to
// the text, duration_s = 3.0 set to `duration`.
fs::path write_scenario(const std::string& shipped, const std::string& fluid, const std::string& name,
                        const std::vector<std::pair<std::string, std::string>>& held, const std::string& duration) {
  const fs::path src = fs::path(SHUDDER_SOURCE_DIR) / "scenarios";
  std::string text = read_text(src / "networks" / shipped);
  for (const auto& [pattern, replacement] : held) {
    const std::string before = text;
    text = std::regex_replace(text, std::regex(pattern), replacement);
    EXPECT_NE(text, before) << shipped << ": no " << pattern;
  }
  text = std::regex_replace(text, std::regex(R"(duration_s = 3\.0)"), "duration_s = " + duration);
  fs::create_directories(kWork / "networks");
  fs::create_directories(kWork / "fluids");
  fs::copy_file(src / "fluids" / fluid, kWork / "fluids" / fluid, fs::copy_options::overwrite_existing);
  const fs::path path = kWork / "networks" / (name + ".toml");
  std::ofstream(path) << text;
  return path;
}

struct Variable {
  std::string name, causality;
  unsigned vr = 0;
  double start = 0.0;
};

// The exported FMU, unpacked, its variables from modelDescription.xml, and the reference run.
struct Exported {
  fs::path scenario, dir;
  std::string guid, xml;
  std::vector<Variable> variables;
  dynamics::Recording run;
};

// Exports `scenario` as NAME.fmu, unpacks it into kWork/NAME/ and runs `reference` (the
// scenario itself, or one of another duration) with --fixed-step 1e-4.
Exported export_and_run(const fs::path& scenario, const fs::path& reference) {
  Exported x;
  x.scenario = scenario;
  const std::string name = scenario.stem().string();
  const fs::path fmu = kWork / (name + ".fmu");
  std::string err;
  EXPECT_EQ(run_cli("export-fmu " + x.scenario.string() + " -o " + fmu.string(), &err), 0) << err;
  x.dir = kWork / name;
  fs::create_directories(x.dir);
  const std::string unzip = "cd " + x.dir.string() + " && " + SHUDDER_CMAKE + " -E tar xf " + fmu.string();
  EXPECT_EQ(std::system(unzip.c_str()), 0);
  x.xml = read_text(x.dir / "modelDescription.xml");
  std::smatch m;
  if (std::regex_search(x.xml, m, std::regex(R"(guid="([^"]+)\")"))) x.guid = m[1];
  const std::regex var(
      R"re(<ScalarVariable name="([^"]+)" valueReference="(\d+)" causality="(\w+)"[^>]*>\s*<Real[^>]*?(?:start="([^"]+)")?/>)re");
  for (auto it = std::sregex_iterator(x.xml.begin(), x.xml.end(), var); it != std::sregex_iterator(); ++it)
    x.variables.push_back({(*it)[1], (*it)[3], static_cast<unsigned>(std::stoul((*it)[2])),
                           (*it)[4].matched ? std::stod((*it)[4]) : 0.0});
  const fs::path h5 = kWork / (reference.stem().string() + ".h5");
  EXPECT_EQ(run_cli("run " + reference.string() + " --fixed-step 1e-4 -o " + h5.string(), &err), 0) << err;
  x.run = io::read_run_hdf5(h5.string());
  return x;
}

const Exported& exported() {
  static const Exported e = [] {
    fs::remove_all(kWork);
    fs::create_directories(kWork);
    const fs::path scenario =
        write_scenario("manual_launch_wet_clutch.toml", "schematic_launch_negative_slope.toml", "launch_held",
                       {{R"(normal_force = \{[^}]*\})", "normal_force = 0.6"}}, "1.0");
    return export_and_run(scenario, scenario);
  }();
  return e;
}

// The Haldex car (header): exported 0.25 s long, its reference run 0.5 s long.
const std::vector<std::pair<std::string, std::string>> kHaldexHeld = {
    {R"(torque_Nm = \{[^}]*\})", "torque_Nm = 100.0"}, {R"(pedal = \{[^}]*\})", "pedal = 0.5882352941176471"}};

const Exported& haldex_exported() {
  static const Exported e = [] {
    (void)exported();  // kWork made afresh
    const fs::path scenario =
        write_scenario("haldex_car_low_mu_uphill.toml", "lsc_fluid_c.toml", "haldex_held", kHaldexHeld, "0.25");
    const fs::path reference = write_scenario("haldex_car_low_mu_uphill.toml", "lsc_fluid_c.toml",
                                              "haldex_held_reference", kHaldexHeld, "0.5");
    return export_and_run(scenario, reference);
  }();
  return e;
}

Fmu& network_fmu() {
  static Fmu f(exported().dir / "binaries/linux64/shudder_network.so");
  return f;
}

Fmu& haldex_fmu() {
  static Fmu f(haldex_exported().dir / "binaries/linux64/shudder_network.so");
  return f;
}

const fmi2CallbackFunctions kCallbacks = {logger, nullptr, nullptr, nullptr, nullptr};

fmi2Component start(Fmu& f, double t0, const Exported& e = exported()) {
  const std::string resources = "file://" + (e.dir / "resources").string();
  fmi2Component c = f.fmi2Instantiate("network", fmi2CoSimulation, e.guid.c_str(), resources.c_str(), &kCallbacks,
                                      fmi2False, fmi2False);
  EXPECT_NE(c, nullptr);
  if (!c) return c;
  EXPECT_EQ(f.fmi2SetupExperiment(c, fmi2False, 0.0, t0, fmi2False, 0.0), fmi2OK);
  EXPECT_EQ(f.fmi2EnterInitializationMode(c), fmi2OK);
  EXPECT_EQ(f.fmi2ExitInitializationMode(c), fmi2OK);
  return c;
}

// The run's channel for an output (FMI names are the channel names here: plain component names).
const dynamics::Signal& channel(const std::string& name, const Exported& e = exported()) {
  const auto* s = e.run.find(name);
  if (!s) throw std::runtime_error("the run has no channel " + name);
  return *s;
}

bool thermal(const std::string& name) { return name.find("temp_C") != std::string::npos; }

// Largest |FMU − run| / (|run| + scale) over the outputs at sample j, per output.
struct Worst {
  double relative = 0.0;
  std::string where;
};

void compare_at(const Exported& e, Fmu& f, fmi2Component c, std::size_t j, bool thermal_too,
                std::map<std::string, double>& scale, Worst& w) {
  for (const auto& v : e.variables) {
    if (v.causality != "output" || (thermal(v.name) && !thermal_too)) continue;
    double value = NAN;
    ASSERT_EQ(f.fmi2GetReal(c, &v.vr, 1, &value), fmi2OK);
    const auto& ref = channel(v.name, e).values;
    double& s = scale[v.name];
    if (s == 0.0) {
      for (double x : ref) s = std::max(s, std::abs(x));
      s = std::max(s, 1e-9);
    }
    const double d = std::abs(value - ref[j]) / s;
    if (!(d <= w.relative)) {
      w.relative = std::isfinite(d) ? d : INFINITY;
      w.where = v.name + " at sample " + std::to_string(j) + ": FMU " + std::to_string(value) + ", run " +
                std::to_string(ref[j]);
    }
  }
}

// Steps from t0 in communication steps of `every` samples, the master's clock t += H; compares
// at each communication point. Thermal outputs are compared at thermal-step ends only (the run
// interpolates them in between, the FMU holds the last thermal step's values).
// Runs to the reference run's end (`e`: the launch or the Haldex car, `f` its library).
Worst master_run(double t0, int every, const Exported& e = exported(), Fmu& f = network_fmu()) {
  fmi2Component c = start(f, t0, e);
  if (!c) return {INFINITY, "no instance"};
  const std::size_t n = channel("time_s", e).values.size();
  const double H = every * 1e-3;  // the runs' sample interval is 1 ms
  Worst w;
  std::map<std::string, double> scale;
  compare_at(e, f, c, 0, true, scale, w);
  double t = t0;
  for (std::size_t j = every; j < n; j += every) {
    EXPECT_EQ(f.fmi2DoStep(c, t, H, fmi2True), fmi2OK);
    t += H;
    compare_at(e, f, c, j, j % 10 == 0, scale, w);
  }
  f.fmi2Terminate(c);
  f.fmi2FreeInstance(c);
  return w;
}

TEST(NetworkFmu, NamesFollowTheStructuredRuleAndUnitsTheirFmiSpelling) {
  // docs/fmu.md "Variables": each dot-separated part keeps [A-Za-z0-9_], any other character
  // becomes '_', a part starting with a digit gets a leading '_'.
  EXPECT_EQ(fmu::fmi_name("launch_clutch.slip_rpm"), "launch_clutch.slip_rpm");
  EXPECT_EQ(fmu::fmi_name("1st-gear.torque_Nm"), "_1st_gear.torque_Nm");
  EXPECT_EQ(fmu::fmi_name("rear axle.speed_rpm"), "rear_axle.speed_rpm");
  EXPECT_EQ(fmu::fmi_unit("N m"), "N.m");
  EXPECT_EQ(fmu::fmi_unit("rpm"), "rpm");
}

TEST(NetworkFmu, ZipMembersCarryTheStandardCrc32) {
  // CRC-32/IEEE's published check value: "123456789" -> 0xCBF43926.
  EXPECT_EQ(io::crc32_of("123456789"), 0xCBF43926ul);
  const std::string zip = io::zip_stored({{"a.txt", "hello"}});
  EXPECT_EQ(zip.substr(0, 4), std::string("PK\x03\x04", 4));
  EXPECT_EQ(zip.substr(30, 5), "a.txt");  // the name after the 30-byte local header
  EXPECT_EQ(zip.substr(35, 5), "hello");  // stored, uncompressed
  EXPECT_THROW(io::zip_stored({{"../x", ""}}), std::invalid_argument);
}

TEST(NetworkFmu, ExportWritesADescriptionWithTheScenariosSignalsAsInputsAndItsChannelsAsOutputs) {
  const Exported& e = exported();
  std::map<std::string, Variable> by_name;
  for (const auto& v : e.variables) by_name[v.name] = v;
  // The inputs: the clutch's normal force and the engine's throttle, started at the scenario's values.
  ASSERT_TRUE(by_name.count("launch_clutch.normal_force"));
  EXPECT_EQ(by_name["launch_clutch.normal_force"].causality, "input");
  EXPECT_EQ(by_name["launch_clutch.normal_force"].start, 0.6);
  ASSERT_TRUE(by_name.count("engine.throttle"));
  EXPECT_EQ(by_name["engine.throttle"].start, 0.0);
  // Every recorded channel but time_s is an output, under its HDF5 name.
  std::size_t outputs = 0;
  for (const auto& s : e.run.signals) {
    if (s.name == "time_s") continue;
    ASSERT_TRUE(by_name.count(s.name)) << s.name;
    EXPECT_EQ(by_name[s.name].causality, "output") << s.name;
    ++outputs;
  }
  std::size_t declared = 0;
  for (const auto& v : e.variables) declared += v.causality == "output";
  EXPECT_EQ(declared, outputs);
  EXPECT_NE(e.xml.find("<DefaultExperiment startTime=\"0\" stopTime=\"1\" stepSize=\"0.001\"/>"), std::string::npos);
  EXPECT_NE(e.xml.find("unit=\"rpm\""), std::string::npos);
  EXPECT_NE(e.xml.find("dependencies=\"\""), std::string::npos);
  // The GUID is the description's content GUID (fmu/content_guid.hpp).
  std::string placeholder = e.xml;
  placeholder.replace(placeholder.find(e.guid), e.guid.size(), "{GUID}");
  EXPECT_EQ(e.guid, fmu::content_guid(placeholder));
  // The scenario and its fluid are in resources/, where the scenario's "../fluids/" finds it.
  EXPECT_TRUE(fs::is_regular_file(e.dir / "resources/network/level1/launch_held.toml"));
  EXPECT_TRUE(fs::is_regular_file(e.dir / "resources/network/fluids/schematic_launch_negative_slope.toml"));
}

TEST(NetworkFmu, ThermalStepCommunicationStepsGiveTheFixedStepRunsValues) {
  // 10 ms steps: the FMU's integrator calls are the run's (header): equal to round-off.
  const Worst w = master_run(0.0, 10);
  EXPECT_LE(w.relative, 1e-12) << w.where;
  std::printf("[ figure ] 10 ms steps from 0 s: largest |FMU - run| / max|run| = %.3g (%s)\n", w.relative,
              w.where.c_str());
}

TEST(NetworkFmu, SampleIntervalStepsFollowTheFixedStepRunAtEverySample) {
  const Worst w = master_run(0.0, 1);
  EXPECT_LE(w.relative, 1e-9) << w.where;
  std::printf("[ figure ] 1 ms steps from 0 s: largest |FMU - run| / max|run| = %.3g (%s)\n", w.relative,
              w.where.c_str());
}

TEST(NetworkFmu, AStartAt1800sRunsAsTheScenarioFromZeroAndATrimmedLastStepEndsAtTheStopTime) {
  // The scenario's t = 0 is the master's start time: 1 ms steps summed on a clock from 1800 s
  // (round-off of 2.3e-13 s per step there, within the step tolerance of fmu/step_split.hpp).
  const Worst w = master_run(1800.0, 1);
  EXPECT_LE(w.relative, 1e-9) << w.where;
  std::printf("[ figure ] 1 ms steps from 1800 s: largest |FMU - run| / max|run| = %.3g (%s)\n", w.relative,
              w.where.c_str());
  // A master stopping at 1800.01045 s trims its last step to 0.45 ms: 4 internal steps and one
  // of half a step, ending at the master's time. The outputs there lie on the run's curve
  // between its samples at 10 and 11 ms: within 5 % of that interval's change of the straight
  // line between them (the speed's curvature over 1 ms; the driveline's 6 Hz mode turns by
  // 2 degrees in it) plus 1e-9 rpm.
  Fmu& f = network_fmu();
  fmi2Component c = start(f, 1800.0);
  ASSERT_NE(c, nullptr);
  double t = 1800.0;
  for (int k = 0; k < 10; ++k, t += 1e-3) ASSERT_EQ(f.fmi2DoStep(c, t, 1e-3, fmi2True), fmi2OK);
  const double last_step = 1800.01045 - t;
  ASSERT_EQ(f.fmi2DoStep(c, t, last_step, fmi2True), fmi2OK);
  fmi2Real last = NAN;
  ASSERT_EQ(f.fmi2GetRealStatus(c, fmi2LastSuccessfulTime, &last), fmi2OK);
  EXPECT_EQ(last, t + last_step);
  for (const char* name : {"crankshaft.speed_rpm", "wheels.speed_rpm", "driveshafts.torque_Nm"}) {
    unsigned vr = 0;
    for (const auto& v : exported().variables)
      if (v.name == name) vr = v.vr;
    double value = NAN;
    ASSERT_EQ(f.fmi2GetReal(c, &vr, 1, &value), fmi2OK);
    const auto& ref = channel(name).values;
    const double line = ref[10] + 0.45 * (ref[11] - ref[10]);
    EXPECT_NEAR(value, line, 0.05 * std::abs(ref[11] - ref[10]) + 1e-9) << name;
  }
  f.fmi2FreeInstance(c);
}

TEST(NetworkFmu, AHaldexCouplingIsExportedWithItsControlUnitsPedalAsAnInput) {
  const Exported& e = haldex_exported();
  std::map<std::string, Variable> by_name;
  for (const auto& v : e.variables) by_name[v.name] = v;
  ASSERT_TRUE(by_name.count("haldex.pedal"));
  EXPECT_EQ(by_name["haldex.pedal"].causality, "input");
  EXPECT_EQ(by_name["haldex.pedal"].start, 0.5882352941176471);
  EXPECT_EQ(by_name["engine_torque.torque_Nm"].start, 100.0);
  // The valve's state and the pack's pressure are outputs (the recorded channels).
  EXPECT_EQ(by_name["haldex.valve_opening"].causality, "output");
  EXPECT_EQ(by_name["haldex.pressure_bar"].causality, "output");
  EXPECT_NE(e.xml.find("<DefaultExperiment startTime=\"0\" stopTime=\"0.25\" stepSize=\"0.001\"/>"), std::string::npos);
}

TEST(NetworkFmu, AHaldexCouplingsControlUnitActsOnTheFmusClockFromItsStartAndPastTheDuration) {
  // The control unit sets the valve every 10 ms on the FMU's clock, which starts at 0 at the
  // master's start time (docs/fmu.md "Time"). The FMU, exported 0.25 s long, runs to 0.5 s and
  // is compared with the run 0.5 s long: its instants go on past the exported duration. That
  // the comparison can tell: the run's valve opening keeps changing after 0.25 s, so a unit
  // that stopped there would hold it.
  const Exported& e = haldex_exported();
  const auto& opening = channel("haldex.valve_opening", e).values;
  ASSERT_EQ(opening.size(), 501u);
  const auto [lo, hi] = std::minmax_element(opening.begin() + 260, opening.end());
  EXPECT_GT(*hi - *lo, 0.05) << "the reference run's unit does not act after 0.25 s: the test would not see it";
  // 10 ms steps from 0 s: the run's integrator calls.
  Worst w = master_run(0.0, 10, e, haldex_fmu());
  EXPECT_LE(w.relative, 1e-12) << w.where;
  std::printf("[ figure ] Haldex car, 10 ms steps from 0 s to 0.5 s: largest |FMU - run| / max|run| = %.3g (%s)\n",
              w.relative, w.where.c_str());
  // 3 ms steps: the unit's instants fall inside communication steps.
  w = master_run(0.0, 3, e, haldex_fmu());
  EXPECT_LE(w.relative, 1e-9) << w.where;
  std::printf("[ figure ] Haldex car, 3 ms steps from 0 s: largest |FMU - run| / max|run| = %.3g (%s)\n", w.relative,
              w.where.c_str());
  // 1 ms steps from 1800 s: the instants are 1800 s + k 10 ms on the master's clock.
  w = master_run(1800.0, 1, e, haldex_fmu());
  EXPECT_LE(w.relative, 1e-9) << w.where;
  std::printf("[ figure ] Haldex car, 1 ms steps from 1800 s: largest |FMU - run| / max|run| = %.3g (%s)\n", w.relative,
              w.where.c_str());
}

TEST(NetworkFmu, AHaldexCouplingsRawPressureSettingIsAnInputThatSetsThePacksPressure) {
  // scenarios/networks/haldex_car_takeup_judder.toml holds the valve's pressure setting at
  // 3 bar (a raw setting, the valve shut below it), 0.2 s long; the pump's pressure rises
  // towards it (1.95 bar at 0.2 s). As exported, the FMU's pressure is the run's; with the
  // input set to 1 bar the pressure levels off at the setting (1.013 bar at 0.2 s: the
  // hydraulics' own response, not a hard cap), well below the run's.
  static const Exported e = [] {
    (void)exported();  // kWork made afresh
    const fs::path scenario =
        write_scenario("haldex_car_takeup_judder.toml", "schematic_negative_slope.toml", "haldex_judder", {}, "0.2");
    return export_and_run(scenario, scenario);
  }();
  std::map<std::string, Variable> by_name;
  for (const auto& v : e.variables) by_name[v.name] = v;
  ASSERT_TRUE(by_name.count("haldex.valve_pressure_bar"));
  EXPECT_EQ(by_name["haldex.valve_pressure_bar"].causality, "input");
  EXPECT_EQ(by_name["haldex.valve_pressure_bar"].start, 3.0);
  static Fmu f(e.dir / "binaries/linux64/shudder_network.so");
  const unsigned pressure = by_name["haldex.pressure_bar"].vr, setting = by_name["haldex.valve_pressure_bar"].vr;
  const auto pressure_at_200ms = [&](double setting_bar) -> double {
    fmi2Component c = start(f, 0.0, e);
    EXPECT_NE(c, nullptr);
    if (!c) return NAN;
    EXPECT_EQ(f.fmi2SetReal(c, &setting, 1, &setting_bar), fmi2OK);
    double t = 0.0;
    for (int k = 0; k < 200; ++k, t += 1e-3) EXPECT_EQ(f.fmi2DoStep(c, t, 1e-3, fmi2True), fmi2OK);
    double p = NAN;
    EXPECT_EQ(f.fmi2GetReal(c, &pressure, 1, &p), fmi2OK);
    f.fmi2FreeInstance(c);
    return p;
  };
  const double run = channel("haldex.pressure_bar", e).values[200];
  const double as_exported = pressure_at_200ms(3.0), lowered = pressure_at_200ms(1.0);
  std::printf(
      "[ figure ] Haldex judder car at 0.2 s: pressure run %.6g bar, FMU %.6g bar, FMU at a 1 bar setting %.6g bar\n",
      run, as_exported, lowered);
  EXPECT_NEAR(as_exported, run, 1e-9 * std::abs(run));
  EXPECT_GT(run, 1.5);
  EXPECT_NEAR(lowered, 1.0, 0.05);
}

TEST(NetworkFmu, Win64DllIsPackedAndGivesTheLinux64OutputsUnderWine) {
  // export-fmu packs the MinGW-w64 build of the network library beside the .so. The same small
  // master (fmu/cross/fmu_load_check.cpp --network) runs both on the Haldex car from 1800 s to
  // 1800.5 s in 1 ms steps (summed clock, last step trimmed), past the exported 0.25 s.
  const Exported& e = haldex_exported();
  const fs::path dll = e.dir / "binaries/win64/shudder_network.dll";
  if (std::string(SHUDDER_FMU_WIN64) != "1") {
    EXPECT_FALSE(fs::exists(dll));
    GTEST_SKIP() << "built without SHUDDER_FMU_WIN64 (no MinGW-w64): the FMU has binaries/linux64 only";
  }
  ASSERT_TRUE(fs::exists(dll));
  expect_win64_dll_exports(dll);
  const std::string wine = SHUDDER_WINE;
  if (wine.empty()) GTEST_SKIP() << "Wine is not installed (wine64): the DLL was checked, not run (docs/fmu.md)";
  std::string vrs;
  std::vector<std::string> names;
  for (const auto& v : e.variables)
    if (v.causality == "output") {
      vrs += " " + std::to_string(v.vr);
      names.push_back(v.name);
    }
  const std::string run = " --network 1800 0.001 1800.5" + vrs;
  const std::string linux_out = command_output(
      std::string(SHUDDER_FMU_LOAD_CHECK) + " " + (e.dir / "binaries/linux64/shudder_network.so").string() +
      " file://" + (e.dir / "resources").string() + " '" + e.guid + "'" + run + "; echo status=$?");
  ASSERT_NE(linux_out.find("status=0"), std::string::npos) << linux_out;
  const std::string prefix = std::string(SHUDDER_FMU_WIN64_BUILD) + "/wineprefix";
  const std::string windows_out = command_output(wine_command(
      wine, prefix,
      std::string(SHUDDER_FMU_WIN64_BUILD) + "/fmu_load_check.exe 'Z:" + dll.string() +
          "' 'file:///Z:" + (e.dir / "resources").string() + "' '" + e.guid + "'" + run + " 2>&1; echo status=$?"));
  ASSERT_NE(windows_out.find("status=0"), std::string::npos) << windows_out;
  std::map<std::string, double> a = name_values(linux_out), b = name_values(windows_out);
  ASSERT_EQ(a.size(), names.size()) << linux_out;
  ASSERT_EQ(b.size(), names.size()) << windows_out;
  // As the clutch FMU's DLL: Windows' own msvcrt may round exp/pow/log differently in the last
  // bit; 1e-9 relative is far above what that carries through 0.5 s.
  double worst = 0.0;
  std::string where;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string vr = std::to_string(fmu::kFirstOutputVr + i);
    ASSERT_TRUE(a.count(vr) && b.count(vr)) << names[i];
    const double d = std::abs(b[vr] - a[vr]) / std::max(1.0, std::abs(a[vr]));
    EXPECT_LE(d, 1e-9) << names[i] << ": linux64 " << a[vr] << ", win64 " << b[vr];
    if (d >= worst) {
      worst = d;
      where = names[i];
    }
  }
  std::printf("[ figure ] win64 DLL under Wine vs linux64, Haldex car 1800-1800.5 s: largest difference %.3g (%s)\n",
              worst, where.c_str());
  // It ran: the pack's pressure built up (the unit shut the valve on the spinning front axle).
  const auto p = std::find(names.begin(), names.end(), "haldex.pressure_bar");
  ASSERT_NE(p, names.end());
  EXPECT_GT(a[std::to_string(fmu::kFirstOutputVr + (p - names.begin()))], 1.0);
}

TEST(NetworkFmu, AnInputReplacesTheScenariosSignal) {
  // The clutch opened by the master (u = 0 from the start, the scenario holds 0.6): its normal
  // force output is 0 N (the run's max_force_N · 0.6 = 1500 N) and it transmits no friction
  // torque (the run's clutch carries the launch).
  Fmu& f = network_fmu();
  fmi2Component c = start(f, 0.0);
  ASSERT_NE(c, nullptr);
  std::map<std::string, unsigned> vr;
  for (const auto& v : exported().variables) vr[v.name] = v.vr;
  const double open = 0.0;
  ASSERT_EQ(f.fmi2SetReal(c, &vr["launch_clutch.normal_force"], 1, &open), fmi2OK);
  double t = 0.0;
  for (int k = 0; k < 100; ++k, t += 1e-3) ASSERT_EQ(f.fmi2DoStep(c, t, 1e-3, fmi2True), fmi2OK);
  double force = NAN, torque = NAN;
  ASSERT_EQ(f.fmi2GetReal(c, &vr["launch_clutch.normal_force_N"], 1, &force), fmi2OK);
  ASSERT_EQ(f.fmi2GetReal(c, &vr["launch_clutch.torque_Nm"], 1, &torque), fmi2OK);
  EXPECT_EQ(channel("launch_clutch.normal_force_N").values[100], 1500.0);
  EXPECT_EQ(force, 0.0);
  EXPECT_GT(std::abs(channel("launch_clutch.torque_Nm").values[100]), 10.0);
  EXPECT_LT(std::abs(torque), 1e-3 * std::abs(channel("launch_clutch.torque_Nm").values[100]));
  f.fmi2FreeInstance(c);
}

TEST(NetworkFmu, InstantiationRefusesAnotherGuid) {
  Fmu& f = network_fmu();
  const std::string resources = "file://" + (exported().dir / "resources").string();
  g_log.clear();
  EXPECT_EQ(f.fmi2Instantiate("network", fmi2CoSimulation, "{00000000-0000-5000-8000-000000000000}", resources.c_str(),
                              &kCallbacks, fmi2False, fmi2False),
            nullptr);
  EXPECT_TRUE(logged("does not match the scenario in the FMU's resources"));
}

TEST(NetworkFmu, Linux64LibraryNeedsNoGlibcNewerThanTheStatedMinimum) {
  const std::string minimum = SHUDDER_FMU_GLIBC_MINIMUM;
  if (minimum.empty()) GTEST_SKIP() << "built without SHUDDER_FMU_GLIBC_2_17: needs the build machine's glibc";
  expect_loads_on_glibc(exported().dir / "binaries/linux64/shudder_network.so", minimum);
}

TEST(NetworkFmu, ANonNetworkScenarioIsOneLineExit2AndNoFmu) {
  (void)exported();  // kWork exists
  const fs::path out = kWork / "not_network.fmu";
  std::string err;
  const std::string rig = (fs::path(SHUDDER_SOURCE_DIR) / "scenarios/rig_case1_25kN_378Hz.toml").string();
  EXPECT_EQ(run_cli("export-fmu " + rig + " -o " + out.string(), &err), 2);
  EXPECT_NE(err.find("scenario.type"), std::string::npos) << err;
  EXPECT_NE(err.find("export-fmu packs network scenarios"), std::string::npos) << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  EXPECT_FALSE(fs::exists(out));
}

TEST(NetworkFmu, AnUnwritableOutputIsOneLineExit2AndNoFmu) {
  const Exported& e = exported();
  std::string err;
  const fs::path out = kWork / "no_such_directory/launch.fmu";
  EXPECT_EQ(run_cli("export-fmu " + e.scenario.string() + " -o " + out.string(), &err), 2);
  EXPECT_NE(err.find("no_such_directory"), std::string::npos) << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  EXPECT_FALSE(fs::exists(out));
  // A directory that exists but takes no files, even from root (/proc): the temporary cannot
  // be created, and nothing is left.
  const int rc = run_cli("export-fmu " + e.scenario.string() + " -o /proc/launch.fmu", &err);
  EXPECT_EQ(rc, 2) << err;
  EXPECT_NE(err.find("cannot create"), std::string::npos) << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  EXPECT_FALSE(fs::exists("/proc/launch.fmu"));
}

}  // namespace
}  // namespace shudder
