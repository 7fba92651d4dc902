// Loading a scenario yields the typed model of its `type`: one minimal scenario per ModelKind
// loads into the variant alternative of that kind, with its kind-specific inputs in place.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "core/model_kind.hpp"
#include "core/overloaded.hpp"
#include "io/input_error.hpp"
#include "io/scenario.hpp"
#include "io/toml_reader.hpp"
#include "rig_models/model.hpp"
#include "tests/support/cli.hpp"

namespace shudder {
namespace {

// Placed beside the shipped scenarios so that the fluid path resolves as theirs do.
const std::string kPath = std::string(SHUDDER_SOURCE_DIR) + "/scenarios/minimal.toml";

std::string minimal_text(ModelKind kind) {
  std::string text = "[scenario]\ntype = \"" + std::string(model_kind_name(kind)) +
                     "\"\nduration_s = 0.5\n\n[clutch]\nfluid = \"fluids/lsc_fluid_c.toml\"\nstart_temp_C = 40.0\n\n";
  if (kind == ModelKind::kDriveline)
    text += "[manoeuvre]\ntime_s = [0.0, 0.5]\nengine_torque_Nm = [0.0, 30.0]\n";
  else
    text += "[drive]\ntime_s = [0.0, 0.5]\nspeed_rpm = [20.0, 40.0]\nnormal_force_N = 15000.0\n";
  return text;
}

TEST(ScenarioModel, EveryKindLoadsIntoItsOwnAlternative) {
  for (const ModelKind kind : kModelKinds) {
    const io::Scenario sc = io::load_scenario_text(minimal_text(kind), kPath);
    EXPECT_EQ(sc.kind(), kind) << model_kind_name(kind);
    EXPECT_EQ(rig_models::kind(sc.model), kind) << model_kind_name(kind);
    EXPECT_EQ(sc.model.index(), static_cast<std::size_t>(kind)) << model_kind_name(kind);
    EXPECT_DOUBLE_EQ(rig_models::duration_s(sc.model), 0.5) << model_kind_name(kind);
  }
}

// Each alternative holds its own inputs: the drive cycle's second speed, the manoeuvre's torque.
TEST(ScenarioModel, KindSpecificInputsReachTheModel) {
  for (const ModelKind kind : kModelKinds) {
    const io::Scenario sc = io::load_scenario_text(minimal_text(kind), kPath);
    std::visit(
        overloaded{
            [](const rig_models::PrescribedSlipModel& m) { EXPECT_DOUBLE_EQ(m.cycle.slip_speed_rpm(0.5), 40.0); },
            [](const rig_models::RigModel& m) {
              EXPECT_DOUBLE_EQ(m.cycle.slip_speed_rpm(0.5), 40.0);
              EXPECT_DOUBLE_EQ(m.settings.sample_rate_Hz, 1000.0);  // the rig's default
            },
            [](const rig_models::DrivelineModel& m) { EXPECT_DOUBLE_EQ(m.manoeuvre.engine_torque_Nm(0.5), 30.0); }},
        sc.model);
  }
}

// The effects outside the clutch are applied to the kinds they act on when the model is built.
TEST(ScenarioModel, BearingDragAndStickTimeReachTheKindsTheyActOn) {
  const std::string effects =
      "\n[effects.bearing_drag]\nenabled = true\n[effects.stick_time_static_friction]\nenabled = true\n";
  const io::Scenario rig = io::load_scenario_text(minimal_text(ModelKind::kRig) + effects, kPath);
  EXPECT_TRUE(std::get<rig_models::RigModel>(rig.model).params.bearing_drag.enabled);
  EXPECT_TRUE(std::get<rig_models::RigModel>(rig.model).params.stick_time.enabled);
  const io::Scenario ps = io::load_scenario_text(minimal_text(ModelKind::kPrescribedSlip) + effects, kPath);
  EXPECT_TRUE(std::get<rig_models::PrescribedSlipModel>(ps.model).settings.bearing_drag.enabled);
  EXPECT_TRUE(ps.stick_time.enabled);
  const std::string stick = "\n[effects.stick_time_static_friction]\nenabled = true\n";
  const io::Scenario dl = io::load_scenario_text(minimal_text(ModelKind::kDriveline) + stick, kPath);
  EXPECT_TRUE(std::get<rig_models::DrivelineModel>(dl.model).params.stick_time.enabled);
}

// [solver] thermal_scheme: "backward_euler" unless asked for. The no-oil-flow variant of Paper G
// Case 1 has no [solver] table (asserted, so the default is what is read); the shipped Case 1
// itself asks for "bdf2" with 40 ms steps, and both reach the model's settings.
TEST(ScenarioModel, ThermalSchemeIsBackwardEulerByDefaultAndBdf2WhenAskedFor) {
  const std::string plain = "scenarios/paper_g_case1_25kN_no_oil_flow.toml";
  ASSERT_EQ(test::slurp(test::source_path(plain)).find("[solver]"), std::string::npos);
  const io::Scenario def = io::load_scenario(test::source_path(plain));
  ASSERT_EQ(def.kind(), ModelKind::kPrescribedSlip);
  EXPECT_EQ(std::get<rig_models::PrescribedSlipModel>(def.model).settings.thermal_scheme,
            rig_models::ThermalScheme::kBackwardEuler);

  const io::Scenario bdf2 = io::load_scenario(test::source_path("scenarios/paper_g_case1_25kN.toml"));
  ASSERT_EQ(bdf2.kind(), ModelKind::kPrescribedSlip);
  const auto& settings = std::get<rig_models::PrescribedSlipModel>(bdf2.model).settings;
  EXPECT_EQ(settings.thermal_scheme, rig_models::ThermalScheme::kBdf2);
  EXPECT_DOUBLE_EQ(settings.thermal_step_s, 0.040);
}

// "bdf2" needs the heat at a thermal step's end, which only the prescribed-slip model has: in a
// rig scenario (the shipped 378 Hz Case 1 with a [solver] table added) and in a driveline one it
// is an input error naming the key and the kind it belongs to. "backward_euler" spelt out loads
// in both (so it is the value, not the table, that is refused).
TEST(ScenarioModel, Bdf2OutsidePrescribedSlipIsAnInputErrorNamingTheKey) {
  const std::string rig_path = test::source_path("scenarios/rig_case1_25kN_378Hz.toml");
  const std::string rig_text = test::slurp(rig_path);
  const auto with_scheme = [](const std::string& text, const std::string& scheme) {
    return text + "\n[solver]\nthermal_scheme = \"" + scheme + "\"\n";
  };
  const std::vector<std::pair<std::string, std::string>> cases = {{rig_text, rig_path},
                                                                  {minimal_text(ModelKind::kDriveline), kPath}};
  for (const auto& [text, path] : cases) {
    EXPECT_NO_THROW((void)io::load_scenario_text(with_scheme(text, "backward_euler"), path)) << path;
    try {
      (void)io::load_scenario_text(with_scheme(text, "bdf2"), path);
      ADD_FAILURE() << "thermal_scheme = \"bdf2\" loaded: " << path;
    } catch (const io::InputError& e) {
      EXPECT_THAT(e.what(), testing::HasSubstr("solver.thermal_scheme"));
      EXPECT_THAT(e.what(), testing::HasSubstr("prescribed_slip"));
    }
  }
}

// A value outside the two is refused with the allowed values listed.
TEST(ScenarioModel, AMisspeltThermalSchemeListsTheAllowedValues) {
  const std::string path = test::source_path("scenarios/paper_g_case1_25kN.toml");
  const std::string text = test::replace(test::slurp(path), "thermal_scheme = \"bdf2\"", "thermal_scheme = \"bdf3\"");
  try {
    (void)io::load_scenario_text(text, path);
    FAIL() << "thermal_scheme = \"bdf3\" loaded";
  } catch (const io::InputError& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr("thermal_scheme"));
    EXPECT_THAT(e.what(), testing::HasSubstr("\"bdf3\" is not allowed"));
    EXPECT_THAT(e.what(), testing::HasSubstr("\"backward_euler\""));
    EXPECT_THAT(e.what(), testing::HasSubstr("\"bdf2\""));
  }
}

}  // namespace
}  // namespace shudder

namespace shudder {
namespace {

// Found by fuzz_scenario: a fluid name with a component longer than the OS allows
// (255 bytes) made std::filesystem::exists throw filesystem_error, which escaped the loader as
// something other than bad input. It must be an InputError naming the key and the OS's reason.
TEST(ScenarioFuzzRegression, FluidPathTheOsRefusesIsBadInput) {
  std::string text = minimal_text(ModelKind::kPrescribedSlip);
  const std::string good = "fluids/lsc_fluid_c.toml";
  text.replace(text.find(good), good.size(), "fluids/" + std::string(300, 'x') + ".toml");
  try {
    (void)io::load_scenario_text(text, kPath);
    FAIL() << "a 300-byte file name loaded";
  } catch (const io::InputError& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr("fluid"));
    EXPECT_THAT(e.what(), testing::HasSubstr("does not exist (File name too long)"));
  }
}

// Found by fuzz_scenario under UBSan (once toml++ was compiled with our flags): a
// code point from U+00A1 to U+0499 where whitespace may stand ("ı", U+0131, as a whole file) made
// toml++ 3.3.0 reach __builtin_unreachable (io/toml_reader.cpp). Such a character is rejected
// before toml++ sees it, with its line; the same characters inside strings and comments, where
// TOML allows them, still load.
TEST(ScenarioFuzzRegression, NonAsciiOutsideStringsAndCommentsIsRejectedWithItsLine) {
  for (const std::string& text : {std::string("\xC4\xB1"), std::string("a = 1\nb = 2 \xC2\xB0\n"),
                                  std::string("a = \"\"\"x\ny\"\"\" \xCE\xBC = 1\n")}) {
    try {
      (void)io::TomlTable::parse_text(text, "u.toml");
      FAIL() << "loaded: " << text;
    } catch (const io::InputError& e) {
      EXPECT_THAT(e.what(), testing::HasSubstr("non-ASCII character outside a string or comment"));
      const std::string line = text.find('\n') == std::string::npos ? "u.toml:1: " : "u.toml:2: ";
      EXPECT_THAT(e.what(), testing::StartsWith(line)) << text;
    }
  }
  const auto t = io::TomlTable::parse_text(
      "\xEF\xBB\xBF# \xCE\xBC at 20 \xC2\xB0"
      "C\nname = \"\xCE\xBC\\\" \xC4\xB1\"\nm = \"\"\"\n\xC4\xB1\"\"\"\n"
      "l = '\xC4\xB1'\nml = \'\'\'\n\xC4\xB1\'\'\'  # \xC4\xB1\n",
      "ok.toml");
  EXPECT_EQ(t["name"].value_or(std::string()), "\xCE\xBC\" \xC4\xB1");
  EXPECT_EQ(t["ml"].value_or(std::string()), "\xC4\xB1");
}

}  // namespace
}  // namespace shudder
