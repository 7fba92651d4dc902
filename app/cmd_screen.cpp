// `shudder screen`: a fluid's friction data screened for vibration risk (docs/screening.md).
// Parsing and printing only: the indices, maps and verdict come from
// studies::screen_fluid (analysis/anti_shudder_indices.hpp underneath).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <string>
#include <variant>
#include <vector>

#include "app/commands.hpp"
#include "app/guarded.hpp"
#include "io/fluid_loader.hpp"
#include "io/input_error.hpp"
#include "io/kind_refusal.hpp"
#include "io/scenario.hpp"
#include "io/screening_json.hpp"
#include "studies/fluid_screening.hpp"

namespace shudder::app {

namespace {

using analysis::Index;

// "40,80,120" -> {40, 80, 120}; InputError on anything else.
std::vector<double> parse_temperatures(const std::string& text) {
  const auto fail = [&](const std::string& why) {
    throw io::InputError("--temps", 0, "",
                         "'" + text + "': " + why + "; give temperatures in degC separated by commas, e.g. 40,80,120");
  };
  std::vector<double> temps;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    const std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    if (item.empty()) fail("empty entry");
    char* end = nullptr;
    const double T = std::strtod(item.c_str(), &end);
    if (end == item.c_str() || *end != '\0') fail("'" + item + "' is not a number");
    if (!std::isfinite(T) || T < -273.15 || T > 1000.0) fail("'" + item + "' is outside -273.15..1000 degC");
    temps.push_back(T);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return temps;
}

std::string fmt(const char* format, double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, x);
  return buf;
}

std::string range(double lo, double hi, const char* format) {
  if (!std::isfinite(lo) && !std::isfinite(hi)) return "any";
  const std::string a = std::isfinite(lo) ? fmt(format, lo) : "-inf";
  const std::string b = std::isfinite(hi) ? fmt(format, hi) : "inf";
  return lo == hi ? a : a + "\u2013" + b;
}

// `s` right-aligned in `width` terminal columns (UTF-8: one column per code point).
std::string pad(const std::string& s, std::size_t width) {
  std::size_t cols = 0;
  for (const char c : s) cols += (static_cast<unsigned char>(c) & 0xC0) != 0x80;
  return std::string(width > cols ? width - cols : 0, ' ') + s;
}

void print_indices(const studies::ScreeningReport& rep) {
  std::printf(
      "\nAnti-shudder indices at %.0f N (* speed outside the law's data: held friction; "
      "! on the risk side):\n",
      rep.load_N);
  std::printf("  %-28s %-9s", "index", "unit");
  for (const auto& at : rep.indices)
    std::printf(" %s", pad(fmt("%.4g", at.temp_C) + (at.temp_outside_data ? "(x)" : "") + " \u00b0C", 10).c_str());
  std::printf("   risk if\n");
  for (std::size_t k = 0; k < analysis::kIndexCount; ++k) {
    const auto idx = static_cast<Index>(k);
    const analysis::IndexInfo& info = analysis::info(idx);
    std::printf("  %-28s %-9s", info.label, info.unit);
    for (const auto& at : rep.indices) {
      const auto& v = at[idx];
      const std::string cell = (std::isfinite(v.value) ? fmt("%.4f", v.value) : std::string("n/a")) +
                               (v.clamped ? "*" : " ") + (analysis::on_risk_side(idx, v.value) ? "!" : " ");
      std::printf(" %s", pad(cell, 10).c_str());
    }
    std::printf("   %s %g\n", info.risk_above ? ">" : "<", info.limit);
  }
  bool any_outside = false;
  for (const auto& at : rep.indices) any_outside = any_outside || at.temp_outside_data;
  if (any_outside) std::printf("  (x) temperature outside the law's data\n");
  if (rep.indices.empty()) std::printf("  (no screening temperature inside the law's data; give --temps)\n");
}

// Runs grouped over consecutive temperatures with the same speed intervals, several groups per
// line: "    40–60 °C: 10–100 rpm | 65 °C: 12–100 rpm | ...".
void print_runs(const std::vector<analysis::RegionRun>& runs, const std::vector<double>& temps) {
  std::vector<std::string> groups;
  std::map<double, std::string> by_temp;
  for (const auto& r : runs) {
    auto& s = by_temp[r.temp_C];
    s += (s.empty() ? "" : ", ") + range(r.from_rpm, r.to_rpm, "%.4g") + " rpm";
  }
  std::size_t j = 0;
  while (j < temps.size()) {
    const auto it = by_temp.find(temps[j]);
    if (it == by_temp.end()) {
      ++j;
      continue;
    }
    std::size_t k = j;
    while (k + 1 < temps.size()) {
      const auto next = by_temp.find(temps[k + 1]);
      if (next == by_temp.end() || next->second != it->second) break;
      ++k;
    }
    groups.push_back(range(temps[j], temps[k], "%.4g") + " \u00b0C: " + it->second);
    j = k + 1;
  }
  std::string line;
  for (const auto& g : groups) {
    if (!line.empty() && line.size() + g.size() > 96) {
      std::printf("    %s\n", line.c_str());
      line.clear();
    }
    line += (line.empty() ? "" : " | ") + g;
  }
  if (!line.empty()) std::printf("    %s\n", line.c_str());
}

void print_slope(const studies::ScreeningReport& rep) {
  const auto& m = rep.slope.dmu_dv_s_per_m;
  const auto& s = rep.slope.speeds_rpm;
  const auto& t = rep.slope.temps_C;
  Eigen::Index i_min = 0, j_min = 0, i_max = 0, j_max = 0;
  const double lo = m.minCoeff(&i_min, &j_min), hi = m.maxCoeff(&i_max, &j_max);
  std::printf(
      "\nIsothermal slope dmu/dv over %s rpm x %s \u00b0C (s/m): min %.4g at %g rpm, %g \u00b0C; "
      "max %.4g at %g rpm, %g \u00b0C\n",
      range(s.front(), s.back(), "%.4g").c_str(), range(t.front(), t.back(), "%.4g").c_str(), lo,
      s[static_cast<std::size_t>(i_min)], t[static_cast<std::size_t>(j_min)], hi, s[static_cast<std::size_t>(i_max)],
      t[static_cast<std::size_t>(j_max)]);
  const auto& e = rep.negative_slope_extent;
  if (e.points == 0) {
    std::printf("  no negative slope on the grid\n");
    return;
  }
  std::printf("  negative slope (risky region) at %d of %d points, %s:\n", e.points, e.grid_points,
              analysis::describe_extent(e).c_str());
  print_runs(rep.negative_slope, t);
}

void print_stability(const studies::ScreeningReport& rep) {
  std::printf("\nStability of steady sliding at %.0f N, isothermal (margin > 0: vibration grows):\n", rep.load_N);
  for (const auto& rig : rep.rigs) {
    const auto& e = rig.unstable_extent;
    std::printf("  %s: ", rig.label.c_str());
    if (e.grid_points == 0)
      std::printf("not judged: no steady sliding anywhere");
    else if (e.points == 0)
      std::printf("stable everywhere");
    else
      std::printf("UNSTABLE at %d of %d points, %s", e.points, e.grid_points, analysis::describe_extent(e).c_str());
    if (e.grid_points > 0)
      std::printf("; largest margin %.4g 1/s at %g rpm, %g \u00b0C (%.1f Hz)", rig.max_margin_per_s, rig.max_margin_rpm,
                  rig.max_margin_temp_C, rig.max_margin_frequency_Hz);
    if (rig.saturated_points > 0) std::printf("; %d points beyond the motor's torque", rig.saturated_points);
    std::printf("\n");
    if (e.points > 0) print_runs(rig.unstable, rig.map.temps_C);
  }
}

}  // namespace

int screen_command(const ScreenOptions& opt) {
  return guarded(opt.fluid, "screening", [&]() -> int {
    // Inputs: fluid, options, optional rig scenario.
    if (std::error_code ec; !std::filesystem::is_regular_file(opt.fluid, ec))
      throw io::InputError(opt.fluid, 0, "",
                           "no such fluid file; give a fluid TOML (docs/formats/fluid_file.md), "
                           "e.g. scenarios/fluids/lsc_fluid_c.toml");
    const clutch::Fluid fluid = io::load_fluid(opt.fluid);
    if (!(std::isfinite(opt.load_N) && opt.load_N > 0))
      throw io::InputError("--load-N", 0, "", "must be a finite normal force > 0 N, e.g. 20000");

    studies::ScreeningOptions so;
    so.indices.load_N = opt.load_N;
    if (!opt.temps.empty()) so.temps_C = parse_temperatures(opt.temps);
    if (!opt.rig.empty()) {
      const io::Scenario sc = io::load_scenario(opt.rig);
      for (const auto& w : sc.warnings) std::cerr << "shudder: warning: " << w << "\n";
      studies::ScreeningRig rig;
      rig.params =
          io::visit_kind(opt.rig, "scenario.type", sc.model,
                         [](const auto& m) -> const rig_models::RigParams& { return rig_models::screening_rig(m); });
      rig.clutch = sc.clutch;
      so.rigs.push_back(rig);
    }

    const studies::ScreeningReport rep = studies::screen_fluid(fluid, so);

    // Report.
    const auto& vr = rep.law_speed_range_mm_s;
    const double per_rpm = analysis::rpm_to_mm_s(1.0, rep.mean_radius_mm);
    std::printf("Fluid %s (%s)\n", rep.fluid_name.c_str(), opt.fluid.c_str());
    std::printf("Speeds at the mean radius %g mm: 1 rpm = %.3f mm/s. Law data: %s mm/s (%s rpm), %s \u00b0C\n",
                rep.mean_radius_mm, per_rpm, range(vr.first, vr.second, "%.4g").c_str(),
                range(vr.first / per_rpm, vr.second / per_rpm, "%.4g").c_str(),
                range(rep.law_temp_range_C.first, rep.law_temp_range_C.second, "%.4g").c_str());
    print_indices(rep);
    print_slope(rep);
    print_stability(rep);
    std::printf("\nVerdict: %s\n", rep.verdict.text.c_str());

    if (!opt.json.empty()) io::write_screening_json(rep, opt.fluid, opt.json);
    // Exit 3: no verdict (docs/screening.md); the JSON is still written, with verdict_level
    // "NOT JUDGED".
    return rep.verdict.level == analysis::RiskLevel::kNotJudged ? 3 : 0;
  });
}

}  // namespace shudder::app
