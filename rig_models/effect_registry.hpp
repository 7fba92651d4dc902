#pragma once
// The one list of switchable physical effects (names fixed by docs/formats/diagnosis_json.md). Each effect is
// declared once, as data: its name and one-line description, its `enabled` switch, its
// parameters (scenario key, unit, scale to the SI member, allowed range, and for the fitted
// ones the diagnosis' bounds and starting guesses), its non-numeric choices, and the model
// kinds it does nothing in. Derived from it, and from nowhere else:
//   * io/scenario.cpp       reads `[effects.NAME]` (keys, ranges, messages, inert-kind warnings)
//   * studies/replay.cpp switches effects on for the diagnosis and lists its candidates
//   * app/                  the default and range of `shudder diagnose --max-effects`
//   * docs/effects.md       the effects tables (tests/rig_models/test_effect_registry.cpp
//                           checks them against this list, and the names against docs/formats/diagnosis_json.md)
// The physics of an effect lives where the effect acts (see the comment at each entry); the
// registry only says which members of the parameter structs carry it.

#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "clutch/wet_clutch.hpp"
#include "core/model_kind.hpp"
#include "components/clutch_contact.hpp"
#include "rig_models/prescribed_slip.hpp"

namespace shudder::rig_models {

/// The parameter structs effects write into, read only (a const model asked which effects it
/// has on).
struct ConstEffectTarget {
  const clutch::WetClutchParams& clutch;
  const components::BearingDrag& bearing_drag;
  const components::StickTimeFriction& stick_time;
  const components::TorqueCell& torque_cell;
  const components::LoadCell& load_cell;
  const components::FrictionDrift& friction_drift;
};

/// The parameter structs effects write into. A scenario builds it from its clutch, bearing drag
/// and stick-time settings; a ReplayModel from its own (studies/replay.hpp).
struct EffectTarget {
  clutch::WetClutchParams& clutch;
  components::BearingDrag& bearing_drag;
  components::StickTimeFriction& stick_time;
  components::TorqueCell& torque_cell;
  components::LoadCell& load_cell;
  components::FrictionDrift& friction_drift;

  operator ConstEffectTarget() const {  // NOLINT: a view
    return {clutch, bearing_drag, stick_time, torque_cell, load_cell, friction_drift};
  }  // NOLINT: a view
};

/// A member of the effect structs, named once by a stateless lambda that serves both
/// constnesses: `[](auto& t) -> auto& { return t.clutch.viscous_gap_m; }`.
template <class Value>
struct EffectMember {
  template <class Locate>
  requires std::is_empty_v<Locate>  // stateless: rebuilt inside the two function pointers
  EffectMember(Locate)              // implicit: registry entries read as data
      : get([](EffectTarget& t) -> Value& { return Locate{}(t); }),
        get_const([](const ConstEffectTarget& t) -> const Value& { return Locate{}(t); }) {}

  Value& operator()(EffectTarget& t) const { return get(t); }
  const Value& operator()(const ConstEffectTarget& t) const { return get_const(t); }

  Value& (*get)(EffectTarget&);
  const Value& (*get_const)(const ConstEffectTarget&);
};

/// Values a scenario key may take (io::Range carries the same fields; it prints them in messages).
struct ValueRange {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_exclusive = false;
  bool max_exclusive = false;

  static ValueRange any() { return {}; }
  static ValueRange positive() { return {0.0, std::numeric_limits<double>::infinity(), true, false}; }
  static ValueRange non_negative() { return {0.0, std::numeric_limits<double>::infinity()}; }
  static ValueRange closed(double lo, double hi) { return {lo, hi}; }
};

/// Scenario key unit -> SI member: member = key × to_si; the key's default = member × to_key.
/// Both factors are kept (not one and its reciprocal) because readers multiply by each.
struct KeyScale {
  double to_key = 1.0;
  double to_si = 1.0;
};
inline constexpr KeyScale kSameUnit{1.0, 1.0};
inline constexpr KeyScale kMicro{1e6, 1e-6};  // µm -> m
inline constexpr KeyScale kMilli{1e3, 1e-3};  // mm -> m

/// How the diagnosis fits a parameter (in the key's unit): bounds are wide physical limits, not
/// priors; the starts span the plausible range so the least-squares fit begins in the right
/// basin. Every fitted parameter of one effect has the same number of starts: start j of the
/// effect is the j-th start of each.
struct FitSpec {
  double lower, upper;  // > 0 (the fit works on log values), unless linear
  std::vector<double> starts;
  bool linear = false;  // a signed parameter (an offset), fitted on linear values
};

struct EffectParameter {
  std::string key;   // in `[effects.NAME]`, as in docs/effects.md
  std::string unit;  // of the key; "-" for dimensionless
  KeyScale scale;
  ValueRange range;  // allowed in a scenario file
  EffectMember<double> member;
  std::optional<FitSpec> fit;  // fitted by the diagnosis when it adds the effect
};

/// A key that takes one of a few strings; `options` in the order of the member's enum values.
struct EffectChoice {
  std::string key;
  std::vector<std::string> options;
  std::size_t (*get)(const ConstEffectTarget&);
  void (*set)(EffectTarget&, std::size_t option);
};

/// A model kind the effect does nothing in, and why (ends the scenario warning and the
/// diagnosis' note of a skipped candidate).
struct InertIn {
  ModelKind kind;
  std::string reason;
};

struct EffectDefinition {
  std::string name;
  std::string description;
  EffectMember<bool> enabled;
  std::vector<EffectParameter> parameters;  // read from a scenario in this order ...
  std::vector<EffectChoice> choices;        // ... then these
  std::vector<InertIn> inert_in;
};

/// Every effect, in docs/formats/diagnosis_json.md order (the order of candidates, messages and docs).
const std::vector<EffectDefinition>& effect_registry();
/// nullptr for a name not in the registry.
const EffectDefinition* find_effect(std::string_view name);
/// "a, b, c": the names, for messages about an unknown effect.
std::string effect_names_list();
/// Why the effect does nothing in a model of this kind; nullopt where it acts.
std::optional<std::string_view> inert_reason(const EffectDefinition& effect, ModelKind kind);
/// The parameters the diagnosis fits, in the order of its parameter vectors.
std::vector<const EffectParameter*> fitted_parameters(const EffectDefinition& effect);

}  // namespace shudder::rig_models
