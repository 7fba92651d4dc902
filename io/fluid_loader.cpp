#include "io/fluid_loader.hpp"

#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "clutch/friction_radius.hpp"
#include "clutch/linear_friction.hpp"
#include "clutch/maki_friction.hpp"
#include "clutch/table_friction.hpp"
#include "io/toml_reader.hpp"

namespace shudder::io {

namespace {

constexpr double kDefaultDensity_kg_m3 = 868.0;  // Paper G Table 1, oil at 40 °C
constexpr double kDefaultMinSpeed_mm_s = 6.0;    // Paper G range rule
constexpr double kDefaultMaxSpeed_mm_s = 590.0;
constexpr const char* kCoefficientNames[4] = {"C1", "C2", "C3", "C4"};

std::string message_number(double x) {
  std::ostringstream os;
  os.precision(10);
  os << x;
  return os.str();
}

// Plausible kinetic friction of a wet clutch: 0 < mu <= 1. mu <= 0 would make friction push
// the sliding surfaces along (negative heat: a sign typo in `beta` gives -4,923 J);
// lubricated paper/steel interfaces run at mu ~ 0.05-0.2 and even dry friction materials stay
// below ~0.6, so mu > 1 can only be a typing error (e.g. a shifted decimal point), not a fluid.
constexpr double kMaxPlausibleMu = 1.0;
// A [linear] law holds for any temperature, so it is checked over the temperatures a wet
// clutch sees: a -40 °C cold start (the Paper G matrix' first row) to 150 °C, the upper end
// of an ATF's continuous service (Paper E measured 30 to ~120 °C). mu is linear in T, so the
// two ends are the extremes.
constexpr double kLinearCheckLow_C = -40.0;
constexpr double kLinearCheckHigh_C = 150.0;
// Speeds per [maki] set at which mu is sampled, log-spaced over [min_speed, max_speed] with
// both ends included: 256 points are 1.8 % apart over the default 6..590 mm/s. Mäki's form
// C1 tanh(C2 v) + C3 v^0.1 + C4 is the sum of two monotone terms, smooth on the scale 1/C2
// (Paper G's C2 <= 0.02 per mm/s, i.e. >= 50 mm/s), so an excursion to mu <= 0 between two
// samples would need a dip narrower than 1.8 % in speed, which the form cannot make there.
constexpr int kMakiSpeedSamples = 256;

// mu must lie in (0, kMaxPlausibleMu]; "" if it does, else what is wrong.
std::string implausible_mu(double mu) {
  if (!(mu > 0.0))
    return "gives mu = " + message_number(mu) +
           " <= 0 (friction would drive the sliding surfaces and "
           "generate negative heat)";
  if (mu > kMaxPlausibleMu)
    return "gives mu = " + message_number(mu) + " > " + message_number(kMaxPlausibleMu) +
           " (implausible for a lubricated clutch, whose mu is ~0.05-0.2)";
  return "";
}

// The speeds at which every [maki] set of a matrix is sampled, with the parts of Mäki's form
// that depend on the speed alone: v^0.1 for every set, tanh(C2 v) for the last rate seen (the
// sets of a matrix often share C2). The check then costs one multiply-add per sample instead of
// a pow and a tanh; the values are MakiSet::mu's bit for bit (same operands, same order).
struct MakiSpeedSamples {
  MakiSpeedSamples(double vmin, double vmax) {
    for (int k = 0; k < kMakiSpeedSamples; ++k) {
      v.push_back(k + 1 == kMakiSpeedSamples
                      ? vmax
                      : vmin * std::pow(vmax / vmin, static_cast<double>(k) / (kMakiSpeedSamples - 1)));
      v_pow.push_back(std::pow(v.back(), 0.1));
    }
  }
  const std::vector<double>& tanh_of(double c2) {
    if (!(c2 == tanh_rate)) {
      tanh_rate = c2;
      tanh_values.resize(v.size());
      for (std::size_t k = 0; k < v.size(); ++k) tanh_values[k] = std::tanh(c2 * v[k]);
    }
    return tanh_values;
  }
  std::vector<double> v, v_pow;
  double tanh_rate = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> tanh_values;
};

// Rejects a [maki] set whose mu leaves (0, 1] anywhere in [vmin, vmax]. The matrix blends the
// mu VALUES of its sets bilinearly in load and temperature (clamped at the ends), so mu at any
// (T, F) is a convex combination of the sets' values: checking each set checks the whole law.
void check_maki_set(TomlTable& row, const clutch::MakiSet& set, std::size_t j, double load_N, double temp_C,
                    MakiSpeedSamples& speeds) {
  const std::vector<double>& th = speeds.tanh_of(set.c2);
  for (std::size_t k = 0; k < speeds.v.size(); ++k) {
    const double mu = set.c1 * th[k] + set.c3 * speeds.v_pow[k] + set.c4;
    if (mu > 0.0 && mu <= kMaxPlausibleMu) continue;
    row.fail("sets", "set " + std::to_string(j) + " " + implausible_mu(mu) + " at speed " +
                         message_number(speeds.v[k]) + " mm/s, temperature " + message_number(temp_C) + " °C, load " +
                         message_number(load_N) + " N; mu must lie in (0, " + message_number(kMaxPlausibleMu) +
                         "] over the law's whole range (min_speed_mm_s..max_speed_mm_s, every "
                         "row and load)");
  }
}

// Rejects an axis that is not strictly increasing, naming the offending element.
void require_increasing(TomlTable& t, const std::string& key, const std::vector<double>& axis) {
  for (std::size_t i = 1; i < axis.size(); ++i)
    if (!(axis[i] > axis[i - 1]))
      t.fail(key, "element " + std::to_string(i) + " = " + message_number(axis[i]) + " is not greater than element " +
                      std::to_string(i - 1) + " = " + message_number(axis[i - 1]) +
                      "; values must be strictly increasing");
}

// One row's `sets`: an array with one [C1, C2, C3, C4] per load, all finite numbers.
std::vector<clutch::MakiSet> read_sets(TomlTable& row, const toml::table& raw_row, const std::vector<double>& loads_N,
                                       double temp_C) {
  const std::string shape =
      "expected an array of " + std::to_string(loads_N.size()) + " sets [C1, C2, C3, C4], one per load in maki.loads_N";
  const toml::node* node = raw_row.get("sets");
  if (!node) row.fail("sets", "missing; " + shape);
  row.mark_read("sets");
  const toml::array* sets = node->as_array();
  if (!sets) row.fail("sets", "is " + std::string(toml_type_name(*node)) + "; " + shape);
  if (sets->size() != loads_N.size())
    row.fail("sets", "has " + std::to_string(sets->size()) + " sets; expected one per load (" +
                         std::to_string(loads_N.size()) + ") in the row at temp_C = " + message_number(temp_C));

  std::vector<clutch::MakiSet> out;
  for (std::size_t j = 0; j < sets->size(); ++j) {
    const std::string which = "set " + std::to_string(j) + " (load " + message_number(loads_N[j]) + " N)";
    const toml::array* c = sets->get(j)->as_array();
    if (!c)
      row.fail("sets",
               which + " is " + std::string(toml_type_name(*sets->get(j))) + "; expected an array [C1, C2, C3, C4]");
    if (c->size() != 4)
      row.fail("sets", which + " has " + std::to_string(c->size()) + " numbers; expected 4 [C1, C2, C3, C4]");
    double v[4] = {};
    for (std::size_t k = 0; k < 4; ++k) {
      const toml::node& e = *c->get(k);
      const std::string elem = which + " " + kCoefficientNames[k];
      if (auto f = e.as_floating_point())
        v[k] = f->get();
      else if (auto i = e.as_integer())
        v[k] = static_cast<double>(i->get());
      else
        row.fail("sets", elem + " is " + std::string(toml_type_name(e)) + "; expected a finite number");
      if (!std::isfinite(v[k])) row.fail("sets", elem + " is not finite (nan/inf); expected a finite number");
    }
    out.push_back({v[0], v[1], v[2], v[3]});
  }
  return out;
}

// A Mäki or table row's temperature (strictly above the previous row's, appended to `temps`)
// and its optional `origin` note.
double read_row_temp(TomlTable& row, std::vector<double>& temps) {
  const double t = row.number("temp_C", Range::closed(-273.15, 1000.0));
  if (!temps.empty() && !(t > temps.back()))
    row.fail("temp_C", "value " + message_number(t) + " is not above the previous row's " +
                           message_number(temps.back()) + "; rows must be strictly increasing in temp_C");
  temps.push_back(t);
  row.string_or("origin", "");
  return t;
}

std::shared_ptr<const clutch::FrictionLaw> read_maki(TomlTable& maki, const toml::table& raw) {
  const double vmin = maki.number_or("min_speed_mm_s", kDefaultMinSpeed_mm_s, Range::positive());
  const double vmax = maki.number_or("max_speed_mm_s", kDefaultMaxSpeed_mm_s, Range::positive());
  if (!(vmax > vmin))
    maki.fail("max_speed_mm_s",
              "value " + message_number(vmax) + " must exceed min_speed_mm_s = " + message_number(vmin));
  const std::vector<double> loads = maki.numbers("loads_N", Range::positive());
  require_increasing(maki, "loads_N", loads);

  std::vector<TomlTable> rows = maki.table_array("row");
  if (rows.empty()) maki.fail("row", "is empty; expected at least one [[maki.row]]");
  const toml::array& raw_rows = *raw.get("row")->as_array();

  std::vector<double> temps;
  std::vector<clutch::MakiSet> sets;  // (n_temp * n_load) row-major
  MakiSpeedSamples speeds(vmin, vmax);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    TomlTable& row = rows[i];
    const double t = read_row_temp(row, temps);
    const auto row_sets = read_sets(row, *raw_rows.get(i)->as_table(), loads, t);
    for (std::size_t j = 0; j < row_sets.size(); ++j) check_maki_set(row, row_sets[j], j, loads[j], t, speeds);
    sets.insert(sets.end(), row_sets.begin(), row_sets.end());
    row.finish();
  }
  maki.finish();
  try {
    return std::make_shared<clutch::MakiFrictionMatrix>(loads, temps, std::move(sets), vmin, vmax);
  } catch (const std::invalid_argument& e) {
    maki.fail("row", e.what());
  }
}

std::shared_ptr<const clutch::FrictionLaw> read_linear(TomlTable& lin) {
  lin.number_or("load_N", 20000.0, Range::positive());  // informational: the lines' test load
  const double radius_mm = lin.number("mean_radius_mm", Range::positive());
  const std::vector<double> rpm = lin.numbers("speeds_rpm", Range::positive());
  require_increasing(lin, "speeds_rpm", rpm);
  const std::vector<double> alpha = lin.numbers("alpha_per_C");
  const std::vector<double> beta = lin.numbers("beta");
  for (const auto& [key, v] : {std::pair{"alpha_per_C", &alpha}, std::pair{"beta", &beta}})
    if (v->size() != rpm.size())
      lin.fail(key, "has " + std::to_string(v->size()) +
                        " elements; expected one per speed in "
                        "speeds_rpm (" +
                        std::to_string(rpm.size()) + ")");
  // mu in (0, 1] over the checked temperatures. Between speeds mu is a convex blend of two
  // lines (weights in [0, 1]) and held beyond the ends, so each line at the two temperature
  // ends covers the whole law exactly.
  for (std::size_t i = 0; i < rpm.size(); ++i)
    for (const double t : {kLinearCheckLow_C, kLinearCheckHigh_C}) {
      const std::string what = implausible_mu(alpha[i] * t + beta[i]);
      if (!what.empty())
        lin.fail("beta", "the line at speed " + message_number(rpm[i]) + " rpm (alpha_per_C[" + std::to_string(i) +
                             "] * T + beta[" + std::to_string(i) + "]) " + what + " at temperature " +
                             message_number(t) + " °C (any load); mu must lie in (0, " +
                             message_number(kMaxPlausibleMu) + "] from " + message_number(kLinearCheckLow_C) + " to " +
                             message_number(kLinearCheckHigh_C) + " °C");
    }
  lin.finish();

  // rpm -> local sliding speed at the mean radius: v = rpm * 2*pi/60 * r
  // (1 rpm = 4.82 mm/s at 46 mm).
  std::vector<clutch::LinearTemperaturePoint> points;
  for (std::size_t i = 0; i < rpm.size(); ++i)
    points.push_back({rpm[i] * 2.0 * std::numbers::pi / 60.0 * radius_mm, alpha[i], beta[i]});
  try {
    return std::make_shared<clutch::LinearTemperatureFriction>(std::move(points));
  } catch (const std::invalid_argument& e) {
    lin.fail("speeds_rpm", e.what());
  }
}

// [table]: mu on speeds_mm_s x [[table.row]] temp_C x loads_N (clutch/table_friction.hpp).
// Each row's `mu` holds one array per load, one value per speed, each in (0, 1]: the law
// blends values convexly and holds them beyond the axes, so the grid bounds the whole law.
// One row's `mu`: an array of arrays of finite numbers (shape checked by the caller).
std::vector<std::vector<double>> read_mu_grid(TomlTable& row, const toml::table& raw_row) {
  const std::string shape = "expected an array with one array of mu values per load";
  const toml::node* node = raw_row.get("mu");
  if (!node) row.fail("mu", "missing; " + shape);
  row.mark_read("mu");
  const toml::array* outer = node->as_array();
  if (!outer) row.fail("mu", "is " + std::string(toml_type_name(*node)) + "; " + shape);
  std::vector<std::vector<double>> out;
  for (std::size_t j = 0; j < outer->size(); ++j) {
    const toml::array* inner = outer->get(j)->as_array();
    if (!inner)
      row.fail("mu",
               "element " + std::to_string(j) + " is " + std::string(toml_type_name(*outer->get(j))) + "; " + shape);
    std::vector<double> values;
    for (std::size_t k = 0; k < inner->size(); ++k) {
      const toml::node& e = *inner->get(k);
      double x = 0.0;
      if (auto f = e.as_floating_point())
        x = f->get();
      else if (auto i = e.as_integer())
        x = static_cast<double>(i->get());
      else
        row.fail("mu", "array " + std::to_string(j) + " element " + std::to_string(k) + " is " +
                           std::string(toml_type_name(e)) + "; expected a finite number");
      if (!std::isfinite(x))
        row.fail("mu", "array " + std::to_string(j) + " element " + std::to_string(k) +
                           " is not finite (nan/inf); expected a finite number");
      values.push_back(x);
    }
    out.push_back(std::move(values));
  }
  return out;
}

std::shared_ptr<const clutch::FrictionLaw> read_table(TomlTable& tab, const toml::table& raw) {
  const std::vector<double> speeds = tab.numbers("speeds_mm_s", Range::positive());
  require_increasing(tab, "speeds_mm_s", speeds);
  const std::vector<double> loads = tab.numbers("loads_N", Range::positive());
  require_increasing(tab, "loads_N", loads);
  std::vector<TomlTable> rows = tab.table_array("row");
  if (rows.empty()) tab.fail("row", "is empty; expected at least one [[table.row]]");
  const toml::array& raw_rows = *raw.get("row")->as_array();
  std::vector<double> temps, mu;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    TomlTable& row = rows[i];
    read_row_temp(row, temps);
    const std::vector<std::vector<double>> grid = read_mu_grid(row, *raw_rows.get(i)->as_table());
    if (grid.size() != loads.size())
      row.fail("mu", "has " + std::to_string(grid.size()) +
                         " arrays; expected one per load in "
                         "table.loads_N (" +
                         std::to_string(loads.size()) + ")");
    for (std::size_t j = 0; j < grid.size(); ++j) {
      if (grid[j].size() != speeds.size())
        row.fail("mu", "array " + std::to_string(j) + " (load " + message_number(loads[j]) + " N) has " +
                           std::to_string(grid[j].size()) +
                           " values; expected one per speed in "
                           "table.speeds_mm_s (" +
                           std::to_string(speeds.size()) + ")");
      for (std::size_t k = 0; k < speeds.size(); ++k) {
        const std::string what = implausible_mu(grid[j][k]);
        if (!what.empty())
          row.fail("mu", "value at speed " + message_number(speeds[k]) + " mm/s, load " + message_number(loads[j]) +
                             " N " + what + "; mu must lie in (0, " + message_number(kMaxPlausibleMu) + "]");
        mu.push_back(grid[j][k]);
      }
    }
    row.finish();
  }
  tab.finish();
  try {
    return std::make_shared<clutch::TableFriction>(speeds, temps, loads, std::move(mu));
  } catch (const std::invalid_argument& e) {
    tab.fail("row", e.what());
  }
}

clutch::Fluid read_fluid(const toml::table& doc, const std::string& path) {
  TomlTable root(doc, path, "");
  clutch::Fluid fluid;

  // [fluid]: identity and viscosity (Walther needs nu40 > nu100 > 0).
  TomlTable f = root.table("fluid");
  fluid.name = f.string("name");
  if (fluid.name.empty()) f.fail("name", "is empty; expected a non-empty fluid name");
  f.string_or("description", "");
  fluid.nu40_cSt = f.number("nu40_cSt", Range::positive());
  fluid.nu100_cSt = f.number("nu100_cSt", Range{0.0, fluid.nu40_cSt, true, true});
  fluid.density_kg_m3 = f.number_or("density_kg_m3", kDefaultDensity_kg_m3, Range::positive());
  f.finish();

  // [static_friction]: mu_s = breakaway_ratio * mu_k(v_min, T, F).
  TomlTable s = root.table("static_friction");
  fluid.breakaway_ratio = s.number("breakaway_ratio", Range::closed(0.5, 3.0));
  s.string_or("source", "");
  s.finish();

  // [friction_radius] (optional): the radius the law was fitted at from torque; a clutch model
  // of another radius converts the law when it is built (clutch/friction_radius.hpp).
  if (root.has("friction_radius")) {
    TomlTable fr = root.table("friction_radius");
    const std::string convention = fr.string("convention");
    clutch::RadiusConvention parsed{};
    if (!clutch::parse_radius_convention(convention, parsed))
      fr.fail("convention", "is '" + convention + "'; expected \"uniform_pressure\" or \"uniform_wear\"");
    fluid.friction_radius_convention = convention;
    fluid.friction_radius_mm = fr.number("radius_mm", Range::positive());
    fr.finish();
  }

  // Exactly one friction law.
  const char* kLaws =
      "[maki] (Paper G matrix), [linear] (Papers B/C/E lines) or [table] "
      "(mu on a speed x temperature x load grid)";
  const int n_laws = int(root.has("maki")) + int(root.has("linear")) + int(root.has("table"));
  if (n_laws > 1)
    root.fail(root.has("maki") && root.has("linear") ? "linear" : "table",
              std::string("given together with [") + (root.has("maki") ? "maki" : "linear") +
                  "]; a fluid has exactly one friction law: " + kLaws);
  if (n_laws == 0) root.fail("maki", std::string("missing; a fluid needs exactly one friction law: ") + kLaws);
  if (root.has("maki")) {
    TomlTable maki = root.table("maki");
    fluid.friction = read_maki(maki, *doc.get("maki")->as_table());
  } else if (root.has("linear")) {
    TomlTable lin = root.table("linear");
    fluid.friction = read_linear(lin);
  } else {
    TomlTable tab = root.table("table");
    fluid.friction = read_table(tab, *doc.get("table")->as_table());
  }
  root.finish();
  return fluid;
}

}  // namespace

clutch::Fluid load_fluid(const std::string& path) {
  // toml++ reads a directory as an empty document; say what is wrong instead.
  std::error_code ec;
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
    throw InputError(path, 0, "", "is not a regular file; expected a fluid TOML file");
  return read_fluid(TomlTable::parse_file(path), path);
}

clutch::Fluid load_fluid_text(const std::string& text, const std::string& path) {
  return read_fluid(TomlTable::parse_text(text, path), path);
}

}  // namespace shudder::io
