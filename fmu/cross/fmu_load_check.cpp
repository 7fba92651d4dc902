// A minimal FMI 2.0 co-simulation master, built for Windows (fmu/cross/, run under Wine by
// tests/fmu) and for Linux (tests/fmu), so the two binaries of the FMU can be run the same way
// and their outputs compared.
//
//   fmu_load_check LIBRARY RESOURCE_URI GUID
//   fmu_load_check LIBRARY RESOURCE_URI GUID --network START STEP STOP VR...
//
// Loads LIBRARY, looks up the fmi2* functions by name and instantiates. The clutch FMU (first
// form): reads the outputs in initialisation mode, runs 0.5 s from start time 1800 s at 0.1 ms
// with the clock summed (t += h, last step trimmed) and a slip and force that change every
// step, then one step of 0.45 ms, and prints "name value" lines (%.17g). A network FMU made by
// `shudder export-fmu` (second form): its inputs at their start values, from START to STOP in
// communication steps of STEP with the clock summed and the last step trimmed, then prints
// "VR value" for each output value reference VR. Exit status 0 when every call returned
// fmi2OK, 1 otherwise, 2 for bad arguments or a library that does not load.
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#ifdef _WIN32
#include <windows.h>
#else
#include <dlfcn.h>
#endif

#include "fmu/fmi2.h"

namespace {

void logger(fmi2ComponentEnvironment, fmi2String, fmi2Status status, fmi2String category, fmi2String message, ...) {
  va_list args;
  va_start(args, message);
  std::fprintf(stderr, "[%d] %s: ", static_cast<int>(status), category);
  std::vfprintf(stderr, message, args);
  std::fprintf(stderr, "\n");
  va_end(args);
}

void* library = nullptr;
void* lookup(const char* name) {
#ifdef _WIN32
  return reinterpret_cast<void*>(GetProcAddress(static_cast<HMODULE>(library), name));
#else
  return dlsym(library, name);
#endif
}

int failures = 0;
void check(fmi2Status s, const char* what) {
  if (s != fmi2OK) {
    std::fprintf(stderr, "%s returned %d\n", what, static_cast<int>(s));
    ++failures;
  }
}

}  // namespace

int main(int argc, char** argv) {
  const bool network = argc >= 9 && std::string(argv[4]) == "--network";
  if (argc != 4 && !network) {
    std::fprintf(stderr, "usage: fmu_load_check LIBRARY RESOURCE_URI GUID [--network START STEP STOP VR...]\n");
    return 2;
  }
#ifdef _WIN32
  library = LoadLibraryA(argv[1]);
#else
  library = dlopen(argv[1], RTLD_NOW | RTLD_LOCAL);
#endif
  if (!library) {
    std::fprintf(stderr, "fmu_load_check: cannot load %s\n", argv[1]);
    return 2;
  }
#define FN(name) auto name = reinterpret_cast<decltype(&::name)>(lookup(#name))
  FN(fmi2Instantiate);
  FN(fmi2SetupExperiment);
  FN(fmi2EnterInitializationMode);
  FN(fmi2ExitInitializationMode);
  FN(fmi2SetReal);
  FN(fmi2GetReal);
  FN(fmi2DoStep);
  FN(fmi2Terminate);
  FN(fmi2FreeInstance);
  FN(fmi2GetStatus);
#undef FN
  if (!fmi2Instantiate || !fmi2SetupExperiment || !fmi2EnterInitializationMode || !fmi2ExitInitializationMode ||
      !fmi2SetReal || !fmi2GetReal || !fmi2DoStep || !fmi2Terminate || !fmi2FreeInstance || !fmi2GetStatus) {
    std::fprintf(stderr, "fmu_load_check: an fmi2 function is missing from %s\n", argv[1]);
    return 2;
  }
  const fmi2CallbackFunctions callbacks = {logger, nullptr, nullptr, nullptr, nullptr};
  fmi2Component c = fmi2Instantiate("check", fmi2CoSimulation, argv[3], argv[2], &callbacks, fmi2False, fmi2False);
  if (!c) {
    std::fprintf(stderr, "fmu_load_check: fmi2Instantiate failed\n");
    return 1;
  }
  if (network) {
    // A network FMU: start values, a summed clock, the last step trimmed to STOP.
    const double t0 = std::atof(argv[5]), H = std::atof(argv[6]), stop = std::atof(argv[7]);
    std::vector<fmi2ValueReference> vr;
    for (int i = 8; i < argc; ++i) vr.push_back(static_cast<fmi2ValueReference>(std::strtoul(argv[i], nullptr, 10)));
    std::vector<double> values(vr.size());
    check(fmi2SetupExperiment(c, fmi2False, 0.0, t0, fmi2True, stop), "fmi2SetupExperiment");
    check(fmi2EnterInitializationMode(c), "fmi2EnterInitializationMode");
    check(fmi2ExitInitializationMode(c), "fmi2ExitInitializationMode");
    for (double t = t0; t < stop - 1e-3 * H;) {
      const double step = t + H > stop - 1e-3 * H ? stop - t : H;
      check(fmi2DoStep(c, t, step, fmi2True), "fmi2DoStep");
      t += step;
    }
    check(fmi2GetReal(c, vr.data(), vr.size(), values.data()), "fmi2GetReal");
    for (std::size_t i = 0; i < vr.size(); ++i) std::printf("%u %.17g\n", vr[i], values[i]);
    check(fmi2Terminate(c), "fmi2Terminate");
    fmi2FreeInstance(c);
    return failures == 0 ? 0 : 1;
  }
  // Value references of fmu/variables.hpp.
  const fmi2ValueReference inputs[] = {0, 1, 2};  // speed a, speed b, clamp force
  const fmi2ValueReference outputs[] = {10, 11, 12, 13, 14, 15, 16, 17, 18};
  const char* names[] = {"torque_Nm",
                         "clutch_torque_Nm",
                         "slip_speed_rad_s",
                         "heat_power_W",
                         "interface_mean_temp_C",
                         "interface_max_temp_C",
                         "thermocouple_temp_C",
                         "ir_temp_C",
                         "sump_temp_C"};
  double out[9] = {};
  const double t0 = 1800.0, stop = 1800.5, h = 1e-4;
  check(fmi2SetupExperiment(c, fmi2False, 0.0, t0, fmi2True, stop), "fmi2SetupExperiment");
  check(fmi2EnterInitializationMode(c), "fmi2EnterInitializationMode");
  const double u0[] = {8.0, 1.0, 15000.0};
  check(fmi2SetReal(c, inputs, 3, u0), "fmi2SetReal");
  check(fmi2GetReal(c, outputs, 9, out), "fmi2GetReal (initialisation mode)");
  std::printf("init_torque_Nm %.17g\ninit_interface_mean_temp_C %.17g\n", out[0], out[4]);
  check(fmi2ExitInitializationMode(c), "fmi2ExitInitializationMode");
  double t = t0;
  for (long k = 0; t < stop; ++k) {
    const double s = static_cast<double>(k) * h;
    const double u[] = {8.0 + 20.0 * s, 1.0, 15000.0 + 8000.0 * std::sin(12.0 * s)};
    check(fmi2SetReal(c, inputs, 3, u), "fmi2SetReal");
    const double step = t + h > stop ? stop - t : h;
    check(fmi2DoStep(c, t, step, fmi2True), "fmi2DoStep");
    t += step;
  }
  check(fmi2DoStep(c, t, 0.00045, fmi2True), "fmi2DoStep (0.45 ms)");
  fmi2Status status = fmi2OK;
  if (fmi2GetStatus(c, fmi2DoStepStatus, &status) != fmi2Discard) {
    std::fprintf(stderr, "fmi2GetStatus did not return fmi2Discard\n");
    ++failures;
  }
  check(fmi2GetReal(c, outputs, 9, out), "fmi2GetReal");
  for (int i = 0; i < 9; ++i) std::printf("%s %.17g\n", names[i], out[i]);
  check(fmi2Terminate(c), "fmi2Terminate");
  fmi2FreeInstance(c);
  return failures == 0 ? 0 : 1;
}
