// Every model kind declares every capability (rig_models/model.hpp), and a kind that cannot do
// something refuses with the text the commands have always printed.
//
// The compile-time half: each alternative of rig_models::Model must have an overload of each
// capability with the declared result. A new kind added to the variant without them fails this
// file's static_assert (and every command's generic visit) instead of falling through.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <concepts>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "io/diagnosis_inputs.hpp"
#include "io/input_error.hpp"
#include "io/kind_refusal.hpp"
#include "io/scenario.hpp"
#include "rig_models/model.hpp"
#include "studies/model_studies.hpp"

namespace shudder {
namespace {

using rig_models::Model;

// One concept per capability, with the result type the commands rely on.
struct Args {
  const clutch::WetClutch& clutch;
  dynamics::Recording& rec;
  const components::StickTimeFriction& stick_time;
};
template <class M>
concept HasKind = requires(const M& m) {
  { rig_models::kind(m) } -> std::same_as<ModelKind>;
  { m.settings.duration_s } -> std::convertible_to<double>;
};
template <class M>
concept Simulates = requires(const M& m, Args a) {
  { rig_models::simulate(m, a.clutch) } -> std::same_as<dynamics::Recording>;
};
template <class M>
concept HasRunAnalysis = requires(const M& m, Args a) {
  { studies::add_run_analysis(m, a.clutch, 40.0, a.rec) } -> std::same_as<std::vector<std::string>>;
  { rig_models::has_rig_plots(m) } -> std::same_as<bool>;
};
template <class M>
concept SaysMeasuredRunExport = requires(const M& m, Args a) {
  { rig_models::measured_run_export(m, a.rec) } -> std::same_as<rig_models::MeasuredExport>;
};
template <class M>
concept SaysSweep = requires(const M& m, Args a) {
  { studies::require_sweep(m) } -> std::same_as<void>;
  { studies::evaluate_case(m, a.clutch, a.rec) } -> std::same_as<studies::CaseOutcome>;
};
template <class M>
concept SaysReplay = requires(const M& m, Args a) {
  { studies::replay_model(m, a.stick_time) } -> std::same_as<studies::ReplayModel>;
};
template <class M>
concept SaysModes = requires(const M& m) {
  { rig_models::modal_subject(m) } -> std::same_as<rig_models::ModalSubject>;
};
template <class M>
concept SaysScreeningRig = requires(const M& m) {
  { rig_models::screening_rig(m) } -> std::same_as<const rig_models::RigParams&>;
};
template <class M>
concept SaysValidation = requires(const M& m) {
  { rig_models::validation_model(m) } -> std::same_as<const rig_models::PrescribedSlipModel&>;
};
template <class M>
concept HasEveryCapability = HasKind<M> && Simulates<M> && HasRunAnalysis<M> && SaysMeasuredRunExport<M> &&
    SaysSweep<M> && SaysReplay<M> && SaysModes<M> && SaysScreeningRig<M> && SaysValidation<M>;

template <std::size_t... I>
constexpr bool every_alternative_has_every_capability(std::index_sequence<I...>) {
  return (HasEveryCapability<std::variant_alternative_t<I, Model>> && ...);
}
static_assert(every_alternative_has_every_capability(std::make_index_sequence<std::variant_size_v<Model>>{}),
              "a model kind lacks a capability overload (rig_models/model.hpp, docs/architecture_kinds.md)");

// A type that is not a kind has none of the capabilities: no catch-all template or default
// overload accepts it, so each check above can fail (a new alternative without its overloads).
struct NotAKind {
  rig_models::PrescribedSlipSettings settings;
};
static_assert(!HasKind<NotAKind>);  // it has settings.duration_s, but no kind()
static_assert(!Simulates<NotAKind> && !HasRunAnalysis<NotAKind> && !SaysMeasuredRunExport<NotAKind> &&
              !SaysSweep<NotAKind> && !SaysReplay<NotAKind> && !SaysModes<NotAKind> && !SaysScreeningRig<NotAKind> &&
              !SaysValidation<NotAKind>);

const std::string kPrescribed = std::string(SHUDDER_SOURCE_DIR) + "/scenarios/paper_g_case1_25kN.toml";
const std::string kRig = std::string(SHUDDER_SOURCE_DIR) + "/scenarios/rig_case1_25kN_378Hz.toml";
const std::string kDriveline = std::string(SHUDDER_SOURCE_DIR) + "/scenarios/driveline_tight_turn.toml";

// What the command prints after "shudder: error: " when `capability` refuses `path`'s model.
template <class Capability>
std::string refusal(const std::string& path, const std::string& key, Capability&& capability) {
  const io::Scenario sc = io::load_scenario(path);
  try {
    io::visit_kind(path, key, sc.model, std::forward<Capability>(capability));
  } catch (const io::InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

// The refusal texts below are the commands' messages before the capabilities moved to the
// kinds (app/cmd_*.cpp at 6fc3277); they must stay byte-identical.
TEST(ModelCapabilities, DrivelineExportsItsCouplingAndReplaysItAlone) {
  // Sweeps accept driveline cases now: the capability passes and a case evaluates.
  EXPECT_EQ(refusal(kDriveline, "scenario.type", [](const auto& m) { studies::require_sweep(m); }), "(accepted)");
  // A measured run of the coupling, replayed through the pack alone.
  const io::Scenario sc = io::load_scenario(kDriveline);
  const auto& dl = std::get<rig_models::DrivelineModel>(sc.model);
  const studies::ReplayModel m = io::replay_model(sc);
  EXPECT_EQ(m.kind, ModelKind::kDriveline);
  EXPECT_EQ(m.settings.thermal_step_s, dl.settings.slow_step_s);
  EXPECT_EQ(m.clutch.thermal.sump_volume_m3, sc.clutch.thermal.sump_volume_m3);  // the pack's own oil
  dynamics::Recording rec;
  for (const char* name :
       {"time_s", "coupling_slip_rpm", "clamp_force_N", "coupling_torque_Nm", "coupling_temp_C", "coupling_oil_temp_C"})
    rec.add_signal(name, "").values = {0.0, 1.0};
  const rig_models::MeasuredExport e = rig_models::measured_run_export(dl, rec);
  EXPECT_EQ(e.rig, "haldex_coupling");
  ASSERT_TRUE(e.coupling.has_value());
  EXPECT_EQ(&e.channels(rec), &*e.coupling);
  const io::Scenario ps = io::load_scenario(kPrescribed);
  const auto ps_export = rig_models::measured_run_export(std::get<rig_models::PrescribedSlipModel>(ps.model), rec);
  EXPECT_EQ(ps_export.rig, "lsctr");
  EXPECT_EQ(&ps_export.channels(rec), &rec);  // the run's own recording, not a copy
}

TEST(ModelCapabilities, KindsWithoutATorsionalNetworkRefuseModesAndScreeningNamingTheirType) {
  const auto modes = [](const auto& m) { return rig_models::modal_subject(m); };
  const auto screening = [](const auto& m) -> const rig_models::RigParams& { return rig_models::screening_rig(m); };
  EXPECT_EQ(refusal(kPrescribed, "scenario.type", modes),
            kPrescribed +
                ": key 'scenario.type': \"prescribed_slip\" has no torsional network; modes needs type = "
                "\"rig\" or \"driveline\"");
  // A driveline's modes are its linearisation about the manoeuvre (accepted).
  EXPECT_EQ(refusal(kDriveline, "scenario.type", modes), "(accepted)");
  EXPECT_EQ(refusal(kPrescribed, "scenario.type", screening),
            kPrescribed +
                ": key 'scenario.type': \"prescribed_slip\" is not a rig; --rig needs a scenario with "
                "type = \"rig\"");
  EXPECT_EQ(refusal(kDriveline, "scenario.type", screening),
            kDriveline +
                ": key 'scenario.type': \"driveline\" is not a rig; --rig needs a scenario with type = "
                "\"rig\"");
}

TEST(ModelCapabilities, OnlyPrescribedSlipIsValidated) {
  const auto validation = [](const auto& m) -> const rig_models::PrescribedSlipModel& {
    return rig_models::validation_model(m);
  };
  EXPECT_EQ(refusal(kRig, "scenario.type", validation),
            kRig + ": key 'scenario.type': is rig; validation compares prescribed_slip runs with the papers");
  EXPECT_EQ(
      refusal(kDriveline, "scenario.type", validation),
      kDriveline + ": key 'scenario.type': is driveline; validation compares prescribed_slip runs with the papers");
  EXPECT_EQ(refusal(kPrescribed, "scenario.type", validation), "(accepted)");
}

// The accepting overloads hand back the kind's own data, not a copy of some default.
TEST(ModelCapabilities, AcceptingKindsYieldTheirOwnModel) {
  const io::Scenario ps = io::load_scenario(kPrescribed);
  const io::Scenario rig = io::load_scenario(kRig);
  const auto& ps_model = std::get<rig_models::PrescribedSlipModel>(ps.model);
  const auto& rig_model = std::get<rig_models::RigModel>(rig.model);
  EXPECT_EQ(&rig_models::validation_model(ps_model), &ps_model);
  EXPECT_EQ(std::get<const rig_models::RigModel*>(rig_models::modal_subject(rig_model)), &rig_model);
  EXPECT_EQ(&rig_models::screening_rig(rig_model), &rig_model.params);
  EXPECT_TRUE(rig_models::has_rig_plots(rig_model));
  EXPECT_FALSE(rig_models::has_rig_plots(ps_model));

  components::StickTimeFriction on;
  on.enabled = true;
  const studies::ReplayModel ps_replay = studies::replay_model(ps_model, on);
  EXPECT_EQ(ps_replay.kind, ModelKind::kPrescribedSlip);
  EXPECT_TRUE(ps_replay.rig_params.stick_time.enabled);  // the scenario's switch reaches the candidate list
  EXPECT_EQ(ps_replay.settings.duration_s, ps_model.settings.duration_s);
  const studies::ReplayModel rig_replay = studies::replay_model(rig_model, on);
  EXPECT_EQ(rig_replay.kind, ModelKind::kRig);
  EXPECT_EQ(rig_replay.rig_params.stick_time.enabled, rig_model.params.stick_time.enabled);  // the rig's own
  EXPECT_EQ(rig_replay.settings.sample_rate_Hz, rig_model.settings.sample_rate_Hz);
  EXPECT_EQ(rig_replay.settings.duration_s, rig_model.settings.duration_s);

  // Every kind stores a verdict block and no map but the rig's; a recording that cannot be
  // judged (here: empty) is a valid run whose block says so, without a warning. (Before the
  // verdict block, prescribed slip left the recording as it was.)
  dynamics::Recording rec;
  EXPECT_TRUE(studies::add_run_analysis(ps_model, ps.make_clutch(), 40.0, rec).empty());
  EXPECT_TRUE(rec.maps.empty());
  ASSERT_EQ(rec.blocks.size(), 1u);
  EXPECT_EQ(rec.blocks.front().find_text("verdict")->value, "not_judged");
  EXPECT_THAT(rec.blocks.front().find_text("reason")->value, ::testing::HasSubstr("no time, torque or slip channel"));
}

}  // namespace
}  // namespace shudder
