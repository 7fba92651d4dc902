// `shudder run`: load a scenario, simulate, write HDF5 (and optionally a measured-run CSV),
// print a readable summary.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <set>

#include "app/commands.hpp"
#include "app/summary.hpp"
#include "io/hdf5_run.hpp"
#include "io/input_error.hpp"
#include "io/measurement_csv.hpp"
#include "io/scenario.hpp"
#include "rig_models/lsctr_rig.hpp"
#include "rig_models/prescribed_slip.hpp"

namespace shudder::app {

int run_command(const RunOptions& opt) {
  try {
    const io::Scenario scenario = io::load_scenario(opt.scenario);
    for (const auto& w : scenario.warnings) std::cerr << "shudder: warning: " << w << "\n";
    const clutch::WetClutch clutch = scenario.make_clutch();

    const auto t0 = std::chrono::steady_clock::now();
    const dynamics::Recording rec =
        scenario.type == "rig"
            ? rig_models::run_rig(scenario.rig, clutch, scenario.cycle, scenario.rig_settings())
            : rig_models::run_prescribed_slip(clutch, scenario.cycle, scenario.settings);
    const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    const std::string out = opt.output.empty() ? scenario.name + ".h5" : opt.output;
    io::write_run_hdf5(out, rec, scenario.text);
    if (!opt.measurement.empty()) {
      io::MeasurementOptions m;
      m.sample_rate_Hz = opt.measurement_rate_Hz;
      m.noise = opt.noise;
      m.seed = opt.seed;
      m.fluid = scenario.fluid.name;
      m.oil_flow_ml_min = scenario.clutch.thermal.supply_flow_m3_s * 6e7;
      char sensor[96];
      std::snprintf(sensor, sizeof sensor, "separator_thermocouple r_mm=%g z_mm=%g",
                    scenario.clutch.thermal.thermocouple_r_m * 1e3,
                    scenario.clutch.thermal.thermocouple_z_m * 1e3);
      m.temp_sensor = sensor;
      io::write_measurement_csv(opt.measurement, rec, m);
    }

    print_run_summary(std::cout, scenario, rec);
    std::cout << "Output: " << out;
    if (!opt.measurement.empty()) std::cout << ", " << opt.measurement;
    std::cout << "\n";
    if (opt.profile) std::cout << "Profile: simulation wall time " << wall_s * 1e3 << " ms\n";
    return 0;
  } catch (const io::InputError& e) {
    std::cerr << "shudder: error: " << e.what() << "\n";
    return 2;
  } catch (const std::invalid_argument& e) {
    std::cerr << "shudder: error: " << opt.scenario << ": " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "shudder: simulation failed: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace shudder::app
