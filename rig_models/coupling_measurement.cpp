#include "rig_models/coupling_measurement.hpp"

#include <stdexcept>
#include <string>

#include "dynamics/signal_names.hpp"

namespace shudder::rig_models {

dynamics::Recording coupling_measurement(const dynamics::Recording& driveline,
                                         const components::TorqueCell& torque_cell,
                                         const components::LoadCell& load_cell) {
  namespace sn = dynamics::signal_names;
  dynamics::Recording out;
  // (column, driveline channel, unit, sensor reading of the true value)
  const auto copy = [&](std::string_view column, std::string_view channel, const char* units, auto read) {
    const dynamics::Signal* s = driveline.find(channel);
    if (!s)
      throw std::invalid_argument("the driveline recording has no " + std::string(channel) +
                                  " channel; a measured coupling run needs it");
    dynamics::Signal c{std::string(column), units, s->values};
    for (double& v : c.values) v = read(v);
    out.signals.push_back(std::move(c));
  };
  const auto as_is = [](double v) { return v; };
  copy(sn::kTime, sn::kTime, "s", as_is);
  copy(sn::kSpeed, sn::kCouplingSlip, "rpm", as_is);
  copy(sn::kNormalForce, sn::kClampForce, "N", [&](double f) { return load_cell.reading_N(f); });
  copy(sn::kTorque, sn::kCouplingTorque, "N m", [&](double m) { return torque_cell.reading_Nm(m); });
  copy(sn::kTemp, sn::kCouplingTemp, "degC", as_is);
  copy(sn::kSumpTemp, sn::kCouplingOilTemp, "degC", as_is);
  return out;
}

}  // namespace shudder::rig_models
