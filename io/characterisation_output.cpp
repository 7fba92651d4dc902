#include "io/characterisation_output.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>

#include "clutch/maki_friction.hpp"
#include "io/screening_json.hpp"

namespace shudder::io {

namespace {

std::string num(double x, int digits = 10) {
  if (!std::isfinite(x)) return "null";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, x);
  std::string s = buf;
  // TOML and JSON both read "1e-05" and "0.1"; keep a decimal point on integers for TOML floats.
  if (s.find_first_of(".en") == std::string::npos) s += ".0";
  return s;
}

std::string nums(const std::vector<double>& v, int digits = 10) {
  std::string s = "[";
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + num(v[i], digits);
  return s + "]";
}

std::string toml_string(const std::string& s) { return json_string(s); }  // basic strings share JSON's escapes

const char* radius_rule(const analysis::FrictionConversion& c) {
  return clutch::radius_convention_name(c.convention());
}

}  // namespace

std::string characterised_fluid_toml(const analysis::Characterisation& c, const analysis::CharacterisationSettings& s,
                                     const FluidIdentity& fluid, const std::vector<std::string>& runs) {
  std::ostringstream o;
  o << "# Made by `shudder characterise` from " << runs.size() << " measured run(s), " << c.used.size()
    << " ramps used, " << c.rejected.size() << " rejected (FIT.json lists them).\n"
    << "# mu = M / (n F r_eff) - mu_bearing: n = " << s.conversion.interfaces
    << ", r_eff = " << num(c.effective_radius_mm, 5) << " mm (" << radius_rule(s.conversion)
    << (s.conversion.source.empty() ? "" : ": " + s.conversion.source)
    << "), mu_bearing = " << num(s.conversion.bearing_drag_mu, 4)
    << "; temperature compensation: " << analysis::compensation_name(s.compensation) << ".\n"
    << "# Data range: " << num(c.min_speed_mm_s, 4) << "-" << num(c.max_speed_mm_s, 4) << " mm/s, "
    << num(c.min_temp_C, 4) << "-" << num(c.max_temp_C, 4) << " °C, " << num(c.loads_N.front(), 5) << "-"
    << num(c.loads_N.back(), 5) << " N. Format: docs/formats/fluid_file.md.\n";
  for (const auto& r : runs) o << "#   run: " << r << "\n";
  o << "\n[fluid]\nname = " << toml_string(fluid.name) << "\n";
  if (!fluid.description.empty()) o << "description = " << toml_string(fluid.description) << "\n";
  o << "nu40_cSt = " << num(fluid.nu40_cSt) << "\nnu100_cSt = " << num(fluid.nu100_cSt)
    << "\ndensity_kg_m3 = " << num(fluid.density_kg_m3)
    << "\n\n[static_friction]\nbreakaway_ratio = " << num(fluid.breakaway_ratio)
    << "\nsource = " << toml_string(fluid.breakaway_source) << "\n\n"
    << "[friction_radius]\n# the radius mu was read at from torque; a model of another radius converts the law\n"
    << "convention = \"" << radius_rule(s.conversion) << "\"\nradius_mm = " << num(c.effective_radius_mm) << "\n\n";
  if (s.law == analysis::LawKind::kMaki) {
    o << "[maki]\nmin_speed_mm_s = " << num(c.min_speed_mm_s) << "\nmax_speed_mm_s = " << num(c.max_speed_mm_s)
      << "\nloads_N = " << nums(c.loads_N) << "\n";
    const auto& law = static_cast<const clutch::MakiFrictionMatrix&>(*c.law);
    for (std::size_t it = 0; it < c.temps_C.size(); ++it) {
      o << "\n[[maki.row]]\ntemp_C = " << num(c.temps_C[it]) << "\norigin = \""
        << (c.temps_C[it] == c.hot_row_temp_C ? "fitted: shudder characterise, the top row's ramps compensated to "
                                                "the hottest temperature they reach (--hot-row)"
                                              : "fitted: shudder characterise")
        << "\"\nsets = [\n";
      for (std::size_t il = 0; il < c.loads_N.size(); ++il) {
        const auto& p = law.set(it, il);
        o << "  " << nums({p.c1, p.c2, p.c3, p.c4}) << ",  # " << num(c.loads_N[il] / 1000.0, 4) << " kN\n";
      }
      o << "]\n";
    }
  } else if (s.law == analysis::LawKind::kLinear) {
    std::vector<double> a, b;
    for (const auto& l : c.lines) {
      a.push_back(l.alpha_per_C);
      b.push_back(l.beta);
    }
    o << "[linear]\nload_N = " << num(c.linear_load_N) << "\nmean_radius_mm = " << num(c.effective_radius_mm)
      << "\nspeeds_rpm = " << nums(c.node_rpm) << "\nalpha_per_C = " << nums(a) << "\nbeta = " << nums(b) << "\n";
  } else {
    o << "[table]\n# speeds: " << nums(c.node_rpm, 4) << " rpm at r_eff\nspeeds_mm_s = " << nums(c.node_speeds_mm_s)
      << "\nloads_N = " << nums(c.loads_N) << "\n";
    for (std::size_t it = 0; it < c.temps_C.size(); ++it) {
      o << "\n[[table.row]]\ntemp_C = " << num(c.temps_C[it]) << "\norigin = \""
        << (c.temps_C[it] == c.hot_row_temp_C ? "measured: shudder characterise, the top row's ramps compensated to "
                                                "the hottest temperature they reach (--hot-row)"
                                              : "measured: shudder characterise")
        << "\"\nmu = [\n";
      for (std::size_t il = 0; il < c.loads_N.size(); ++il) {
        std::vector<double> row;
        for (double v : c.node_speeds_mm_s) row.push_back(c.law->mu(v, c.temps_C[it], c.loads_N[il]));
        o << "  " << nums(row, 6) << ",  # " << num(c.loads_N[il] / 1000.0, 4) << " kN\n";
      }
      o << "]\n";
    }
  }
  return o.str();
}

std::string characterisation_json(const analysis::Characterisation& c, const analysis::CharacterisationSettings& s,
                                  const std::vector<std::string>& runs, const std::string& fluid_path) {
  std::ostringstream o;
  o << "{\n  \"format\": \"shudder-characterisation/1\",\n  \"fluid_file\": " << json_string(fluid_path)
    << ",\n  \"runs\": [";
  for (std::size_t i = 0; i < runs.size(); ++i) o << (i ? ", " : "") << json_string(runs[i]);
  o << "],\n  \"law\": \"" << analysis::law_name(s.law) << "\",\n  \"compensation\": \""
    << analysis::compensation_name(s.compensation)
    << "\",\n  \"alpha_per_C\": " << (s.compensation == analysis::Compensation::kLinear ? num(c.alpha_per_C) : "null")
    << ",\n  \"alpha_fitted\": " << (c.alpha_fitted ? "true" : "false") << ",\n  \"radius\": {\"rule\": \""
    << radius_rule(s.conversion) << "\", \"source\": " << json_string(s.conversion.source)
    << ", \"effective_mm\": " << num(c.effective_radius_mm) << ", \"interfaces\": " << s.conversion.interfaces
    << ", \"bearing_drag_mu\": " << num(s.conversion.bearing_drag_mu) << "},\n  \"ranges\": {\"speed_mm_s\": ["
    << num(c.min_speed_mm_s) << ", " << num(c.max_speed_mm_s) << "], \"temp_C\": [" << num(c.min_temp_C) << ", "
    << num(c.max_temp_C) << "], \"load_N\": [" << num(c.loads_N.front()) << ", " << num(c.loads_N.back())
    << "]},\n  \"hot_row_temp_C\": " << num(c.hot_row_temp_C) << ",\n  \"loads_N\": " << nums(c.loads_N)
    << ",\n  \"temps_C\": " << nums(c.temps_C) << ",\n  \"node_rpm\": " << nums(c.node_rpm) << ",\n  \"ramps_used\": [";
  for (std::size_t i = 0; i < c.used.size(); ++i) {
    const auto& r = c.used[i];
    o << (i ? "," : "") << "\n    {\"run\": " << json_string(runs[r.run]) << ", \"t_start_s\": " << num(r.t_start_s)
      << ", \"t_end_s\": " << num(r.t_end_s) << ", \"direction\": \"" << analysis::direction_name(r.direction)
      << "\", \"load_N\": " << num(r.load_N) << ", \"start_temp_C\": " << num(r.start_temp_C)
      << ", \"reference_temp_C\": " << num(c.used_ref_temp_C[i]) << "}";
  }
  o << "\n  ],\n  \"ramps_rejected\": [";
  for (std::size_t i = 0; i < c.rejected.size(); ++i) {
    const auto& r = c.rejected[i];
    o << (i ? "," : "") << "\n    {\"run\": " << json_string(runs[r.run]) << ", \"t_start_s\": " << num(r.t_start_s)
      << ", \"t_end_s\": " << num(r.t_end_s) << ", \"reason\": " << json_string(r.reason) << "}";
  }
  o << "\n  ],\n  \"rows\": [";
  for (std::size_t i = 0; i < c.rows.size(); ++i) {
    const auto& r = c.rows[i];
    o << (i ? "," : "") << "\n    {\"load_N\": " << num(r.load_N) << ", \"temp_C\": " << num(r.temp_C)
      << ", \"ramps_up\": " << r.ramps_up << ", \"ramps_down\": " << r.ramps_down << ", \"speed_mm_s\": ["
      << num(r.min_speed_mm_s) << ", " << num(r.max_speed_mm_s) << "], \"temp_range_C\": [" << num(r.min_temp_C) << ", "
      << num(r.max_temp_C) << "], \"rms_residual\": " << num(r.rms_residual)
      << ", \"max_residual\": " << num(r.max_residual) << ", \"up_down_gap_raw\": " << num(r.up_down_gap_raw)
      << ", \"up_down_gap_compensated\": " << num(r.up_down_gap_comp);
    if (s.law == analysis::LawKind::kMaki)
      o << ", \"maki\": " << nums({r.maki[0], r.maki[1], r.maki[2], r.maki[3]})
        << ", \"maki_standard_error\": " << nums({r.maki_se[0], r.maki_se[1], r.maki_se[2], r.maki_se[3]});
    o << ", \"node_mu\": " << nums(r.node_mu) << "}";
  }
  o << "\n  ],\n  \"warnings\": [";
  for (std::size_t i = 0; i < c.warnings.size(); ++i) o << (i ? ", " : "") << json_string(c.warnings[i]);
  o << "]";
  if (!c.quadratic.empty()) {
    o << ",\n  \"quadratic\": [";
    for (std::size_t i = 0; i < c.quadratic.size(); ++i) {
      const auto& q = c.quadratic[i];
      o << (i ? "," : "") << "\n    {\"load_N\": " << num(q.load_N) << ", \"rpm\": " << num(q.rpm)
        << ", \"a\": " << num(q.a) << ", \"b\": " << num(q.b) << ", \"c\": " << num(q.c) << ", \"ramps\": " << q.ramps
        << ", \"rms\": " << num(q.rms) << "}";
    }
    o << "\n  ]";
  }
  if (!c.piecewise.empty()) {
    o << ",\n  \"piecewise\": [";
    for (std::size_t i = 0; i < c.piecewise.size(); ++i)
      o << (i ? "," : "") << "\n    {\"load_N\": " << num(c.piecewise[i].load_N)
        << ", \"temp_knots_C\": " << nums(c.piecewise[i].temp_knots_C) << ", \"rms\": " << num(c.piecewise[i].rms)
        << "}";
    o << "\n  ]";
  }
  if (!c.lines.empty()) {
    o << ",\n  \"linear_load_N\": " << num(c.linear_load_N) << ",\n  \"lines\": [";
    for (std::size_t i = 0; i < c.lines.size(); ++i) {
      const auto& l = c.lines[i];
      o << (i ? "," : "") << "\n    {\"rpm\": " << num(l.rpm) << ", \"alpha_per_C\": " << num(l.alpha_per_C)
        << ", \"beta\": " << num(l.beta) << ", \"alpha_standard_error\": " << num(l.alpha_se)
        << ", \"beta_standard_error\": " << num(l.beta_se) << "}";
    }
    o << "\n  ]";
  }
  o << "\n}\n";
  return o.str();
}

namespace {

// One method's rows: residuals of its law against its own (compensated) bin means, and its parameters.
std::string method_json(const analysis::Characterisation& c, const analysis::CharacterisationSettings& s,
                        double torque_rms_Nm) {
  std::ostringstream o;
  double worst_rms = 0.0, worst_max = 0.0;
  for (const auto& r : c.rows) {
    worst_rms = std::max(worst_rms, r.rms_residual);
    worst_max = std::max(worst_max, r.max_residual);
  }
  o << "{\"compensation\": \"" << analysis::compensation_name(s.compensation)
    << "\", \"replayed_torque_rms_Nm\": " << num(torque_rms_Nm) << ", \"max_rms_residual\": " << num(worst_rms)
    << ", \"max_residual\": " << num(worst_max) << ", \"rows\": [";
  for (std::size_t i = 0; i < c.rows.size(); ++i) {
    const auto& r = c.rows[i];
    o << (i ? "," : "") << "\n      {\"load_N\": " << num(r.load_N) << ", \"temp_C\": " << num(r.temp_C)
      << ", \"rms_residual\": " << num(r.rms_residual) << ", \"max_residual\": " << num(r.max_residual);
    if (s.law == analysis::LawKind::kMaki)
      o << ", \"maki\": " << nums({r.maki[0], r.maki[1], r.maki[2], r.maki[3]})
        << ", \"maki_standard_error\": " << nums({r.maki_se[0], r.maki_se[1], r.maki_se[2], r.maki_se[3]});
    std::vector<double> law_mu;
    for (double v : c.node_speeds_mm_s) law_mu.push_back(c.law->mu(v, r.temp_C, r.load_N));
    o << ", \"law_node_mu\": " << nums(law_mu) << "}";
  }
  o << "\n    ]";
  if (!c.lines.empty()) {
    std::vector<double> a, b;
    for (const auto& l : c.lines) {
      a.push_back(l.alpha_per_C);
      b.push_back(l.beta);
    }
    o << ", \"alpha_per_C\": " << nums(a) << ", \"beta\": " << nums(b);
  }
  o << "}";
  return o.str();
}

}  // namespace

std::string characterisation_json(const studies::InverseCharacterisation& r,
                                  const analysis::CharacterisationSettings& s, const std::vector<std::string>& runs,
                                  const std::string& fluid_path) {
  std::string doc = characterisation_json(r.inverse, r.settings, runs, fluid_path);
  doc.resize(doc.size() - 3);  // "\n}\n": the document continues
  std::ostringstream o;
  o << doc
    << ",\n  \"method\": \"inverse\",\n  \"temperature\": \"model_interface_mean\",\n  \"methods\": {\n    "
       "\"node_rpm\": "
    << nums(r.inverse.node_rpm) << ",\n    \"sensor\": " << method_json(r.sensor, s, r.torque_rms_sensor_Nm)
    << ",\n    \"inverse\": " << method_json(r.inverse, r.settings, r.torque_rms_Nm)
    << ",\n    \"thermal_calibration\": {\"oil_flow_e\": [" << num(r.oil_flow_start.e) << ", " << num(r.oil_flow.e)
    << "], \"oil_flow_a\": [" << num(r.oil_flow_start.a) << ", " << num(r.oil_flow.a)
    << "], \"oil_flow_b\": " << num(r.oil_flow.b) << ", \"temp_rms_C\": [" << num(r.temp_rms_start_C) << ", "
    << num(r.temp_rms_C) << "]},\n    \"law_updates\": " << r.iterations << ", \"replays\": " << r.replays
    << ", \"last_change_mu\": " << num(r.last_change_mu) << "\n  }\n}\n";
  return o.str();
}

std::string with_breakaway_json(std::string doc, const analysis::BreakawayMeasurement& m, double written_ratio,
                                const std::string& source) {
  doc.resize(doc.size() - 3);  // "\n}\n": the document continues
  std::ostringstream o;
  o << doc << ",\n  \"breakaway\": {\"ratio\": " << num(written_ratio) << ", \"source\": " << json_string(source)
    << ", \"measured\": " << (m.ratio ? "true" : "false");
  if (!m.ratio) o << ", \"not_measured\": " << json_string(m.not_measured);
  o << ", \"starts_from_rest\": [";
  for (std::size_t i = 0; i < m.events.size(); ++i) {
    const auto& e = m.events[i];
    o << (i ? "," : "") << "\n    {\"run\": " << e.run << ", \"t_peak_s\": " << num(e.t_peak_s)
      << ", \"speed_rpm\": " << num(e.speed_rpm) << ", \"temp_C\": " << num(e.temp_C)
      << ", \"load_N\": " << num(e.load_N) << ", \"mu_peak\": " << num(e.mu_peak)
      << ", \"mu_kinetic\": " << num(e.mu_kinetic) << ", \"ratio\": " << num(e.ratio) << "}";
  }
  o << "]}\n}\n";
  return o.str();
}

}  // namespace shudder::io
