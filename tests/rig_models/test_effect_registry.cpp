// The effect registry (rig_models/effect_registry.hpp) against what derives from it and what
// documents it. Checked:
//   * docs/effects.md carries the registry's tables exactly (names, descriptions, defaults,
//     parameters, units, allowed ranges, fit bounds and starts); on a mismatch the test prints
//     the tables to paste;
//   * the diagnosis JSON's contract (docs/formats/diagnosis_json.md) names the registry's effects
//     plus those docs/effects.md lists as not modelled yet, and no others;
//   * a scenario's `[effects.NAME]` and the diagnosis' enable_effect set the same members with the
//     same scales (values written through the registry come back equal from a loaded scenario);
//   * enable_effect's and the scenario reader's errors name the effect or the valid ones;
//   * applicability per model kind: stick-time friction is a candidate on the rig only.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "io/diagnosis_inputs.hpp"
#include "io/input_error.hpp"
#include "io/scenario.hpp"
#include "io/toml_reader.hpp"
#include "rig_models/effect_registry.hpp"
#include "studies/replay.hpp"
#include "tests/support/cli.hpp"

namespace shudder {
namespace {

using rig_models::effect_registry;
using rig_models::EffectDefinition;

std::string fmt(double x) {
  std::ostringstream os;
  os.precision(10);  // as io::Range::describe prints bounds
  os << x;
  return os.str();
}

std::string list(const std::vector<double>& xs) {
  std::string s;
  for (double x : xs) s += (s.empty() ? "" : ", ") + fmt(x);
  return s;
}

io::Range toml_range(const rig_models::ValueRange& r) { return {r.min, r.max, r.min_exclusive, r.max_exclusive}; }

// The parameter structs as a scenario that omits `[effects]` has them.
struct Defaults {
  clutch::WetClutchParams clutch;
  components::BearingDrag bearing_drag;
  components::StickTimeFriction stick_time;
  components::TorqueCell torque_cell;
  components::LoadCell load_cell;
  components::FrictionDrift friction_drift;
  rig_models::EffectTarget target() {
    return {clutch, bearing_drag, stick_time, torque_cell, load_cell, friction_drift};
  }
};

// The two tables docs/effects.md must carry (effects; parameters), generated from the registry.
std::vector<std::string> expected_docs_tables() {
  Defaults d;
  const auto t = d.target();
  std::string s =
      "| effect | default | what it is | does nothing in |\n"
      "|---|---|---|---|\n";
  for (const auto& e : effect_registry()) {
    std::string inert;
    for (const auto& i : e.inert_in)
      inert += (inert.empty() ? "" : "; ") + std::string("`") + std::string(model_kind_name(i.kind)) + "` (" +
               i.reason + ")";
    s += "| `" + e.name + "` | " + (e.enabled(t) ? "on" : "off") + " | " + e.description + " | " +
         (inert.empty() ? "—" : inert) + " |\n";
  }
  std::string p_table =
      "| effect | key | unit | allowed | default | fit bounds | fit starts |\n"
      "|---|---|---|---|---|---|---|\n";
  for (const auto& e : effect_registry()) {
    for (const auto& p : e.parameters)
      p_table += "| `" + e.name + "` | `" + p.key + "` | " + p.unit + " | " + toml_range(p.range).describe() + " | " +
                 fmt(p.member(t) * p.scale.to_key) + " | " +
                 (p.fit ? "[" + fmt(p.fit->lower) + ", " + fmt(p.fit->upper) + "]" : std::string("—")) + " | " +
                 (p.fit ? list(p.fit->starts) : std::string("—")) + " |\n";
    for (const auto& c : e.choices) {
      std::string options;
      for (const auto& o : c.options) options += (options.empty() ? "" : " or ") + ("`\"" + o + "\"`");
      p_table += "| `" + e.name + "` | `" + c.key + "` | choice | " + options + " | `\"" + c.options.at(c.get(t)) +
                 "\"` | — | — |\n";
    }
  }
  return {s, p_table};
}

// Every `name` in backticks in `text`.
std::vector<std::string> backticked(const std::string& text) {
  std::vector<std::string> out;
  for (std::size_t a = text.find('`'); a != std::string::npos; a = text.find('`', a + 1)) {
    const std::size_t b = text.find('`', a + 1);
    if (b == std::string::npos) break;
    out.push_back(text.substr(a + 1, b - a - 1));
    a = b;
  }
  return out;
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

// docs/effects.md's line "Named in the diagnosis format, not modelled yet: `a`, `b`."
std::set<std::string> docs_not_modelled(const std::string& docs) {
  const std::string prefix = "Named in the diagnosis format, not modelled yet:";
  for (const auto& l : lines(docs))
    if (l.rfind(prefix, 0) == 0) {
      const auto names = backticked(l);
      return {names.begin(), names.end()};
    }
  ADD_FAILURE() << "docs/effects.md has no line starting \"" << prefix << "\"";
  return {};
}

// The names of docs/formats/diagnosis_json.md's effect table (header "| name | what the effect is |"); a row may
// name several effects ("`torque_sensor_gain`, `torque_sensor_offset`").
std::vector<std::string> formats_effect_names(const std::string& formats) {
  std::vector<std::string> names;
  bool in_table = false;
  for (const auto& l : lines(formats)) {
    if (!in_table) {
      in_table = l.rfind("| name | what the effect is |", 0) == 0;
      continue;
    }
    if (l.empty() || l[0] != '|') break;
    if (l.rfind("|---", 0) == 0) continue;
    const auto first_cell = l.substr(1, l.find('|', 1) - 1);
    for (auto& n : backticked(first_cell)) names.push_back(n);
  }
  EXPECT_TRUE(in_table)
      << "docs/formats/diagnosis_json.md: no effect table with header \"| name | what the effect is |\"";
  return names;
}

TEST(EffectRegistry, IsWellFormed) {
  std::set<std::string> names;
  for (const auto& e : effect_registry()) {
    EXPECT_TRUE(names.insert(e.name).second) << "duplicate effect " << e.name;
    EXPECT_FALSE(e.description.empty()) << e.name;
    const auto fitted = rig_models::fitted_parameters(e);
    for (const auto* p : fitted) {
      // The fit works on log values (signed offsets on linear ones); every starting guess lies
      // within the bounds, and start j of the effect takes the j-th start of each parameter, so
      // all have as many.
      if (!p->fit->linear) {
        EXPECT_GT(p->fit->lower, 0.0) << e.name << "." << p->key;
      }
      EXPECT_LT(p->fit->lower, p->fit->upper) << e.name << "." << p->key;
      EXPECT_EQ(p->fit->starts.size(), fitted.front()->fit->starts.size()) << e.name << "." << p->key;
      for (double x : p->fit->starts) {
        EXPECT_GE(x, p->fit->lower) << e.name << "." << p->key;
        EXPECT_LE(x, p->fit->upper) << e.name << "." << p->key;
      }
    }
  }
  std::string joined;
  for (const auto& e : effect_registry()) {
    EXPECT_EQ(rig_models::find_effect(e.name), &e);
    joined += (joined.empty() ? "" : ", ") + e.name;
  }
  EXPECT_EQ(rig_models::effect_names_list(), joined);
  EXPECT_EQ(rig_models::find_effect("magic_cooling"), nullptr);
}

TEST(EffectRegistry, DocsTablesEqualTheRegistry) {
  const std::string docs = test::slurp(test::source_path("docs/effects.md"));
  for (const auto& table : expected_docs_tables())
    EXPECT_NE(docs.find(table), std::string::npos)
        << "docs/effects.md does not carry this table of the registry; it should read:\n\n"
        << table;
}

TEST(EffectRegistry, DiagnosisFormatNamesTheSameEffects) {
  const auto not_modelled = docs_not_modelled(test::slurp(test::source_path("docs/effects.md")));
  for (const auto& e : effect_registry())
    EXPECT_EQ(not_modelled.count(e.name), 0u) << e.name << " is modelled but docs/effects.md lists it as not yet";
  std::set<std::string> expected = not_modelled;
  for (const auto& e : effect_registry()) expected.insert(e.name);
  const auto names = formats_effect_names(test::slurp(test::source_path("docs/formats/diagnosis_json.md")));
  EXPECT_EQ(std::set<std::string>(names.begin(), names.end()), expected)
      << "docs/formats/diagnosis_json.md's effects = the registry's + docs/effects.md's not-modelled list";
  EXPECT_EQ(names.size(), expected.size()) << "docs/formats/diagnosis_json.md names an effect twice";
}

// A value of the parameter in its key's unit, within its range and unlike its default.
double probe_value(const rig_models::EffectParameter& p, rig_models::EffectTarget t) {
  if (p.fit) return p.fit->starts.back();
  const double d = p.member(t) * p.scale.to_key;
  return d != 0.0 ? d * 0.75 : 0.25;
}

TEST(EffectRegistry, ScenarioReaderAndDiagnosisSetTheSameMembers) {
  const std::string base = test::shipped_scenario_text("diagnosis_probe.toml");
  for (const auto& e : effect_registry()) {
    if (e.parameters.empty()) continue;
    SCOPED_TRACE(e.name);
    // Through the registry on a model: every parameter set in SI, the effect switched on.
    studies::ReplayModel expected;
    auto target = studies::effect_target(expected);
    e.enabled(target) = true;
    std::ostringstream toml;
    toml.precision(17);  // round-trips a double through the text
    toml << "\n[effects." << e.name << "]\nenabled = true\n";
    std::vector<double> fitted_values;  // key units, in the order enable_effect takes them
    for (const auto& p : e.parameters) {
      const double v = probe_value(p, target);
      ASSERT_TRUE(toml_range(p.range).contains(v)) << p.key;
      ASSERT_NE(v, p.member(target) * p.scale.to_key) << p.key << ": the probe must differ from the default";
      p.member(target) = v * p.scale.to_si;
      toml << p.key << " = " << v << "\n";
      if (p.fit) fitted_values.push_back(v);
    }
    // Through a scenario file: the reader must land each value in the same member, same scale.
    const auto loaded =
        io::replay_model(io::load_scenario_text(base + toml.str(), test::source_path("scenarios/x.toml")));
    EXPECT_TRUE(studies::effect_enabled(loaded, e.name));
    const auto want = studies::effect_target(std::as_const(expected));
    for (const auto& p : e.parameters)  // same operations on the same value: equal, not close
      EXPECT_EQ(p.member(studies::effect_target(loaded)), p.member(want)) << p.key;

    // And the diagnosis' enable_effect with the same values (its fitted ones) lands them there too.
    studies::ReplayModel enabled;
    auto enabled_target = studies::effect_target(enabled);
    for (const auto& p : e.parameters)
      if (!p.fit) p.member(enabled_target) = p.member(want);  // not fitted: as the scenario set it
    studies::enable_effect(enabled, e.name, fitted_values);
    EXPECT_TRUE(studies::effect_enabled(enabled, e.name));
    for (const auto& p : e.parameters)
      EXPECT_EQ(p.member(studies::effect_target(std::as_const(enabled))), p.member(want)) << p.key;
  }
}

TEST(EffectRegistry, ChoiceIsReadIntoItsMember) {
  const std::string base = test::shipped_scenario_text("diagnosis_probe.toml");
  const auto s = io::load_scenario_text(
      base + "\n[effects.interface_oil_cooling]\nenabled = true\nfilm_advection = \"film_energy_balance\"\n",
      test::source_path("scenarios/x.toml"));
  EXPECT_EQ(s.clutch.thermal.oil_flow.form, clutch::FilmAdvectionForm::kFilmEnergyBalance);
  const auto d = io::load_scenario_text(base, test::source_path("scenarios/x.toml"));
  EXPECT_EQ(d.clutch.thermal.oil_flow.form, clutch::FilmAdvectionForm::kPaperGLiteral);
}

TEST(EffectRegistry, EnableEffectChecksNameAndValueCount) {
  studies::ReplayModel m;
  try {
    studies::enable_effect(m, "rig_heat_capacity", {150.0});
    ADD_FAILURE() << "one value for a two-parameter effect was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "effect rig_heat_capacity takes 2 parameters, got 1");
  }
  try {
    studies::enable_effect(m, "magic_cooling", {});
    ADD_FAILURE() << "an unknown effect was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()),
              "unknown effect 'magic_cooling'; valid effects are: " + rig_models::effect_names_list());
  }
  EXPECT_THROW(studies::effect_enabled(m, "magic_cooling"), std::invalid_argument);
}

TEST(EffectRegistry, ScenarioRejectsAnUnknownEffectListingTheValidOnes) {
  const std::string text =
      test::shipped_scenario_text("diagnosis_probe.toml") + "\n[effects.magic_cooling]\nenabled = true\n";
  try {
    io::load_scenario_text(text, test::source_path("scenarios/x.toml"));
    ADD_FAILURE() << "an unknown effect was accepted";
  } catch (const io::InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("effects.magic_cooling"), std::string::npos) << what;
    EXPECT_NE(what.find("unknown effect; valid effects are: " + rig_models::effect_names_list()), std::string::npos)
        << what;
  }
}

bool is_candidate(const std::vector<analysis::EffectCandidate>& cs, const std::string& name) {
  return std::any_of(cs.begin(), cs.end(), [&](const auto& c) { return c.name == name; });
}

TEST(EffectRegistry, StickTimeIsACandidateOnTheRigOnly) {
  studies::ReplayModel slip;
  std::vector<std::string> skipped;
  const auto slip_candidates = studies::replay_candidates(slip, &skipped);
  EXPECT_FALSE(is_candidate(slip_candidates, "stick_time_static_friction"));
  EXPECT_EQ(skipped, std::vector<std::string>{"stick_time_static_friction: the slip is imposed, nothing sticks"});
  EXPECT_TRUE(is_candidate(slip_candidates, "bearing_drag"));

  studies::ReplayModel rig;
  rig.kind = ModelKind::kRig;
  skipped.clear();
  const auto rig_candidates = studies::replay_candidates(rig, &skipped);
  EXPECT_TRUE(is_candidate(rig_candidates, "stick_time_static_friction"));
  const std::string loop = ": the rig's torque cell also drives its speed loop; not modelled there yet";
  EXPECT_EQ(skipped, (std::vector<std::string>{
                         "torque_sensor_gain" + loop, "torque_sensor_offset" + loop,
                         "friction_drift: the rig's contact law does not accumulate the sliding distance yet"}));
  // Default model: every effect off by default and active on the rig is a candidate, each
  // once, in registry order.
  std::vector<std::string> expected;
  Defaults d;
  for (const auto& e : effect_registry())
    if (!e.enabled(d.target()) && !rig_models::inert_reason(e, ModelKind::kRig)) expected.push_back(e.name);
  std::vector<std::string> got;
  for (const auto& c : rig_candidates) got.push_back(c.name);
  EXPECT_EQ(got, expected);
}

TEST(EffectRegistry, InertEffectsWarnInTheirScenarioKinds) {
  const std::string slip =
      test::shipped_scenario_text("diagnosis_probe.toml") + "\n[effects.stick_time_static_friction]\nenabled = true\n";
  const auto s = io::load_scenario_text(slip, test::source_path("scenarios/x.toml"));
  EXPECT_EQ(s.warnings, std::vector<std::string>{"effect stick_time_static_friction has no effect in a "
                                                 "prescribed_slip scenario (the slip is imposed, nothing sticks)"});
  const std::string rig = test::shipped_scenario_text("rig_stick_time_probe.toml") +
                          "\n[effects.stick_time_static_friction]\nenabled = true\n";
  EXPECT_TRUE(io::load_scenario_text(rig, test::source_path("scenarios/x.toml")).warnings.empty());
}

}  // namespace
}  // namespace shudder
