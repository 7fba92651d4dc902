// Recording -> measured run (see measurement_csv.hpp): built once in memory (resampling, noise),
// then written as CSV here or as HDF5 by measured_run.cpp. Numbers are formatted with
// std::to_chars, so the output does not depend on the C locale.
#include "io/measurement_csv.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <limits>
#include <numbers>
#include <random>
#include <string_view>
#include <vector>

#include "core/units.hpp"
#include "dynamics/signal_names.hpp"
#include "io/atomic_file.hpp"
#include "io/input_error.hpp"

namespace shudder::io {
namespace {

// One output column: its recorded values and the noise it gets.
struct Column {
  std::string_view name;  // dynamics/signal_names.hpp
  double sigma;           // noise standard deviation, column unit
  bool non_negative;      // clip noisy values at 0 (normal force)
  std::vector<double> values;
};

// Standard normal deviates from std::mt19937_64 (sequence fixed by the standard) by Box-Muller,
// so a seed gives the same numbers with every standard library.
class StandardNormal {
 public:
  explicit StandardNormal(unsigned seed) : rng_(seed) {}
  double operator()() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    const double u1 = uniform_open(), u2 = uniform_open();
    const double radius = std::sqrt(-2.0 * std::log(u1));
    spare_ = radius * std::sin(2.0 * std::numbers::pi * u2);
    has_spare_ = true;
    return radius * std::cos(2.0 * std::numbers::pi * u2);
  }

 private:
  // Uniform on (0, 1): the top 53 bits, centred in their interval (never 0, so log() is finite).
  double uniform_open() { return (static_cast<double>(rng_() >> 11) + 0.5) * 0x1.0p-53; }
  std::mt19937_64 rng_;
  bool has_spare_ = false;
  double spare_ = 0.0;
};

std::string format(double v, std::chars_format how, int precision) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, v, how, precision);
  return std::string(buf, res.ptr);
}

// Fewest decimals (>= 3) at which the printed times stay strictly increasing and within 1 % of
// the smallest step of the true times.
int time_decimals(const std::vector<double>& t) {
  double min_step = t[1] - t[0];
  for (std::size_t k = 2; k < t.size(); ++k) min_step = std::min(min_step, t[k] - t[k - 1]);
  for (int d = 3; d < 17; ++d) {
    bool good = true;
    double previous = -std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < t.size() && good; ++k) {
      const std::string text = format(t[k], std::chars_format::fixed, d);
      double printed = 0.0;
      std::from_chars(text.data(), text.data() + text.size(), printed);
      good = printed > previous && std::abs(printed - t[k]) <= 0.01 * min_step;
      previous = printed;
    }
    if (good) return d;
  }
  return 17;
}

// Values of (t, v) linearly interpolated at ascending `t_new`, all within [t.front(), t.back()].
std::vector<double> interpolate(const std::vector<double>& t, const std::vector<double>& v,
                                const std::vector<double>& t_new) {
  std::vector<double> out;
  out.reserve(t_new.size());
  std::size_t j = 0;  // t[j] <= tq <= t[j + 1]
  for (double tq : t_new) {
    while (j + 2 < t.size() && t[j + 1] < tq) ++j;
    const double w = (tq - t[j]) / (t[j + 1] - t[j]);
    out.push_back(w == 0.0 ? v[j] : w == 1.0 ? v[j + 1] : v[j] + w * (v[j + 1] - v[j]));
  }
  return out;
}

void check_options(const std::string& path, const MeasurementOptions& opt) {
  const double rate = opt.sample_rate_Hz;
  if (!std::isfinite(rate) || rate < 0.0 || rate > 1e6)
    throw InputError(path, 0, "sample_rate_Hz",
                     "got " + format(rate, std::chars_format::general, 6) +
                         "; use 0 (the recording's own rate) or a rate in (0, 1e6] Hz");
  if (!std::isfinite(opt.oil_flow_ml_min) || opt.oil_flow_ml_min < 0.0)
    throw InputError(path, 0, "oil_flow_ml_min", "must be a finite value >= 0 ml/min");
  for (const auto& [key, text] : {std::pair{"rig", &opt.rig}, std::pair{"fluid", &opt.fluid},
                                  std::pair{"clutch", &opt.clutch}, std::pair{"temp_sensor", &opt.temp_sensor}})
    if (text->find_first_of("\r\n") != std::string::npos)
      throw InputError(path, 0, key, "metadata value must be a single line");
}

// The sensor columns in output order, checked as the format's reader would check them.
std::vector<Column> sensor_columns(const std::string& path, const dynamics::Recording& rec,
                                   const std::vector<double>& time) {
  using A = SensorAccuracy;
  constexpr double k = A::sigma_per_accuracy;
  namespace sn = dynamics::signal_names;
  std::vector<Column> cols = {
      {sn::kSpeed, k * A::speed_rpm, false, {}},         {sn::kNormalForce, k * A::normal_force_N, true, {}},
      {sn::kTorque, k * A::torque_Nm, false, {}},        {sn::kTemp, k * A::thermocouple_C, false, {}},
      {sn::kSumpTemp, k * A::thermocouple_C, false, {}}, {sn::kIrTemp, k * A::ir_C, false, {}}};
  constexpr std::size_t n_required = 4;
  std::vector<Column> present;
  for (std::size_t c = 0; c < cols.size(); ++c) {
    const dynamics::Signal* s = rec.find(cols[c].name);
    if (!s && c < n_required)
      throw InputError(path, 0, std::string(cols[c].name),
                       "recording has no such signal; a measured run needs time_s, speed_rpm, "
                       "normal_force_N, torque_Nm and temp_C");
    if (!s) continue;
    if (s->values.size() != time.size()) throw InputError(path, 0, s->name, "signal length differs from time_s");
    for (std::size_t i = 0; i < time.size(); ++i) {
      if (!std::isfinite(s->values[i]))
        throw InputError(path, 0, s->name, "non-finite value at t = " + std::to_string(time[i]) + " s");
      if (cols[c].non_negative && s->values[i] < 0.0)
        throw InputError(path, 0, s->name, "negative value at t = " + std::to_string(time[i]) + " s");
    }
    cols[c].values = s->values;
    present.push_back(std::move(cols[c]));
  }
  return present;
}

const std::vector<double>& recorded_time(const std::string& path, const dynamics::Recording& rec) {
  const dynamics::Signal* t = rec.find(dynamics::signal_names::kTime);
  if (!t) throw InputError(path, 0, "time_s", "recording has no time_s signal");
  if (t->values.size() < 2) throw InputError(path, 0, "time_s", "recording has fewer than 2 samples");
  for (std::size_t i = 0; i < t->values.size(); ++i)
    if (!std::isfinite(t->values[i]) || (i > 0 && !(t->values[i] > t->values[i - 1])))
      throw InputError(path, 0, "time_s", "not finite and strictly increasing at sample " + std::to_string(i));
  return t->values;
}

// Metadata lines, header, rows: time with the fewest decimals that keep it exact enough (see
// time_decimals), every other value with 6 significant digits.
void write_csv(const std::string& path, const MeasuredRun& run) {
  const std::string tmp = temp_path_for(path);
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError(path, 0, "", "cannot create '" + tmp + "'; check the directory exists and is writable");
    for (const auto& [key, value] : run.metadata) out << "# " << key << ": " << value << '\n';
    for (std::size_t c = 0; c < run.columns.size(); ++c) out << (c == 0 ? "" : ",") << run.columns[c].name;
    out << '\n';
    const std::vector<double>& time = run.columns.front().values;
    const int decimals = time_decimals(time);
    std::string line;
    for (std::size_t i = 0; i < time.size(); ++i) {
      line = format(time[i], std::chars_format::fixed, decimals);
      for (std::size_t c = 1; c < run.columns.size(); ++c)
        (line += ',') += format(run.columns[c].values[i], std::chars_format::general, 6);
      line += '\n';
      out << line;
    }
    out.close();
    if (out.fail()) {
      discard_temp_file(tmp);
      throw InputError(path, 0, "", "cannot write '" + tmp + "' (disk full?)");
    }
  }
  commit_temp_file(tmp, path);
}

bool has_hdf5_extension(const std::string& path) {
  const auto ends_with = [&](std::string_view ext) {
    return path.size() > ext.size() && std::equal(ext.rbegin(), ext.rend(), path.rbegin(), [](char a, char b) {
             return a == std::tolower(static_cast<unsigned char>(b));
           });
  };
  return ends_with(".h5") || ends_with(".hdf5");
}

}  // namespace

MeasuredRun make_measurement(const std::string& path, const dynamics::Recording& rec, const MeasurementOptions& opt) {
  check_options(path, opt);
  const std::vector<double>& t_rec = recorded_time(path, rec);
  std::vector<Column> cols = sensor_columns(path, rec, t_rec);

  // Output times: the recording's own, or t0 + k / rate up to t_end.
  const double t0 = t_rec.front(), t_end = t_rec.back();
  double rate = opt.sample_rate_Hz;
  std::vector<double> time = t_rec;
  if (rate == 0.0) {
    rate = static_cast<double>(t_rec.size() - 1) / (t_end - t0);  // mean rate
  } else {
    const auto n = static_cast<std::size_t>(std::floor((t_end - t0) * rate + 1e-9)) + 1;
    time.resize(n);
    for (std::size_t k = 0; k < n; ++k) time[k] = std::min(t0 + static_cast<double>(k) / rate, t_end);
    for (auto& c : cols) c.values = interpolate(t_rec, c.values, time);
  }
  if (time.size() < measured_run_min_rows)
    throw InputError(
        path, 0, "sample_rate_Hz",
        "only " + std::to_string(time.size()) + " rows; the format needs at least 10: raise the rate or record longer");

  // Sensor noise, drawn row by row, columns in output order.
  if (opt.noise) {
    StandardNormal normal(opt.seed);
    for (std::size_t i = 0; i < time.size(); ++i)
      for (auto& c : cols) {
        c.values[i] += c.sigma * normal();
        if (c.non_negative && c.values[i] < 0.0) c.values[i] = 0.0;
      }
  }

  MeasuredRun run;
  run.path = path;
  const auto g6 = [](double v) { return format(v, std::chars_format::general, 6); };
  auto& meta = run.metadata;
  meta.emplace_back("format", std::string(measured_run_format));
  if (!opt.rig.empty()) meta.emplace_back("rig", opt.rig);
  if (!opt.fluid.empty()) meta.emplace_back("fluid", opt.fluid);
  if (!opt.clutch.empty()) meta.emplace_back("clutch", opt.clutch);
  if (!opt.temp_sensor.empty()) meta.emplace_back("temp_sensor", opt.temp_sensor);
  meta.emplace_back("oil_flow_ml_min", g6(opt.oil_flow_ml_min));
  meta.emplace_back("sample_rate_Hz", g6(rate));
  meta.emplace_back("noise", opt.noise ? "on" : "off");
  if (opt.noise) meta.emplace_back("seed", std::to_string(opt.seed));
  run.columns.push_back(
      {std::string(dynamics::signal_names::kTime), measured_run_units(dynamics::signal_names::kTime), std::move(time)});
  for (auto& c : cols) run.columns.push_back({std::string(c.name), measured_run_units(c.name), std::move(c.values)});
  return run;
}

void write_measured_run_csv(const std::string& path, const MeasuredRun& run) { write_csv(path, run); }

void write_measurement_csv(const std::string& path, const dynamics::Recording& rec, const MeasurementOptions& opt) {
  write_csv(path, make_measurement(path, rec, opt));
}

void write_measurement(const std::string& path, const dynamics::Recording& rec, const MeasurementOptions& opt) {
  if (has_hdf5_extension(path))
    write_measured_run_hdf5(path, make_measurement(path, rec, opt));
  else
    write_measurement_csv(path, rec, opt);
}

void describe_clutch(MeasurementOptions& opt, const clutch::WetClutchParams& clutch, const std::string& fluid_name) {
  opt.fluid = fluid_name;
  opt.oil_flow_ml_min = units::m3_s_to_ml_min(clutch.thermal.supply_flow_m3_s);
  char sensor[96];
  std::snprintf(sensor, sizeof sensor, "separator_thermocouple r_mm=%g z_mm=%g", clutch.thermal.thermocouple_r_m * 1e3,
                clutch.thermal.thermocouple_z_m * 1e3);
  opt.temp_sensor = sensor;
}

}  // namespace shudder::io
