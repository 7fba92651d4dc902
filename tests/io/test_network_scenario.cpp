// Network scenario files: the reference in docs/formats/network_file.md equals the declarations the
// reader uses; a bad network is one line naming the component, its line and what to change.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>

#include "io/input_error.hpp"
#include "io/network_components.hpp"
#include "studies/network_run.hpp"
#include "io/network_scenario.hpp"
#include "tests/support/cli.hpp"

namespace shudder::io {
namespace {

TEST(NetworkComponents, DocsTablesEqualTheDeclarations) {
  const std::string docs = test::slurp(test::source_path("docs/formats/network_file.md"));
  const std::string begin = "<!-- BEGIN GENERATED REFERENCE -->\n", end = "<!-- END GENERATED REFERENCE -->";
  const auto a = docs.find(begin), b = docs.find(end);
  ASSERT_NE(a, std::string::npos);
  ASSERT_NE(b, std::string::npos);
  const std::string section = docs.substr(a + begin.size(), b - a - begin.size());
  // SHUDDER_WRITE_DOCS=1 rewrites the section from the declarations (after changing them).
  if (const char* w = std::getenv("SHUDDER_WRITE_DOCS"); w && std::string(w) == "1") {
    std::ofstream(test::source_path("docs/formats/network_file.md"))
        << docs.substr(0, a + begin.size()) << network_reference_markdown() << docs.substr(b);
    return;
  }
  EXPECT_EQ(section, network_reference_markdown())
      << "docs/formats/network_file.md's reference section should read:\n\n"
      << network_reference_markdown();
}

// Two inertias joined by a plain clutch; `extra` is appended (more components or keys).
std::string two_inertias(const std::string& extra) {
  return R"([scenario]
type = "network"
duration_s = 1.0
[network.engine_side]
type = "inertia"
inertia_kg_m2 = 0.2
speed_rpm = 1000
[network.wheel_side]
type = "inertia"
inertia_kg_m2 = 0.5
[network.clutch]
type = "clutch"
from = "engine_side"
to = "wheel_side"
mu = 0.1
mean_radius_m = 0.1
interfaces = 2
max_force_N = 1000
)" + extra;
}

// The error's text, or "" when the file loads.
std::string error_of(const std::string& text) {
  try {
    load_network_scenario_text(text, "net.toml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(NetworkScenario, AGoodNetworkLoads) {
  const auto sc = load_network_scenario_text(two_inertias(""), "net.toml");
  EXPECT_EQ(sc.spec.inertias.size(), 2u);
  ASSERT_EQ(sc.spec.clutches.size(), 1u);
  EXPECT_DOUBLE_EQ(sc.spec.clutches[0].plain.geometry_factor_m, 0.2);  // 2 interfaces x 0.1 m
}

TEST(NetworkScenario, AMisspeltNodeNamesTheNearest) {
  std::string text = two_inertias("");
  text.replace(text.find("to = \"wheel_side\""), 17, "to = \"wheel_sde\"");
  const std::string e = error_of(text);
  EXPECT_NE(e.find("net.toml:"), std::string::npos) << e;
  EXPECT_NE(e.find("network.clutch"), std::string::npos) << e;
  EXPECT_NE(e.find("did you mean 'wheel_side'"), std::string::npos) << e;
}

TEST(NetworkScenario, AMisspeltTypeNamesTheNearest) {
  const std::string e =
      error_of(two_inertias("[network.spring]\ntype = \"shfat\"\nfrom = \"engine_side\"\nto = \"ground\"\n"));
  EXPECT_NE(e.find("did you mean 'shaft'"), std::string::npos) << e;
}

TEST(NetworkScenario, AComponentJoinedToItselfIsRefused) {
  const std::string e = error_of(two_inertias(
      "[network.spring]\ntype = \"shaft\"\nfrom = \"wheel_side\"\nto = \"wheel_side\"\nstiffness_Nm_per_rad = 100\n"));
  EXPECT_NE(e.find("network.spring"), std::string::npos) << e;
  EXPECT_NE(e.find("joined to itself"), std::string::npos) << e;
}

TEST(NetworkScenario, AMasslessNodeNothingFixesIsRefused) {
  const std::string e =
      error_of(two_inertias("[network.hub]\ntype = \"inertia\"\ninertia_kg_m2 = 0\n[network.spring]\ntype = "
                            "\"shaft\"\nfrom = \"wheel_side\"\n"
                            "to = \"hub\"\nstiffness_Nm_per_rad = 100\n"));
  EXPECT_NE(e.find("network.hub"), std::string::npos) << e;
  EXPECT_NE(e.find("no inertia"), std::string::npos) << e;
}

TEST(NetworkScenario, GearsThatCloseALoopAreRefused) {
  const std::string e = error_of(
      two_inertias("[network.g1]\ntype = \"gear\"\ninput = \"engine_side\"\noutput = \"wheel_side\"\nratio = 3\n"
                   "[network.g2]\ntype = \"gear\"\ninput = \"engine_side\"\noutput = \"wheel_side\"\nratio = 2\n"));
  EXPECT_NE(e.find("network.g2"), std::string::npos) << e;
  EXPECT_NE(e.find("ratios disagree"), std::string::npos) << e;
  // The same loop with agreeing ratios fixes nothing new: over-constrained.
  const std::string same = error_of(
      two_inertias("[network.g1]\ntype = \"gear\"\ninput = \"engine_side\"\noutput = \"wheel_side\"\nratio = 3\n"
                   "[network.g2]\ntype = \"gear\"\ninput = \"engine_side\"\noutput = \"wheel_side\"\nratio = 3\n"));
  EXPECT_NE(same.find("network.g2"), std::string::npos) << same;
  EXPECT_NE(same.find("over-constrains"), std::string::npos) << same;
}

TEST(NetworkScenario, APartNothingDrivesIsRefused) {
  const std::string e = error_of(two_inertias("[network.island]\ntype = \"inertia\"\ninertia_kg_m2 = 1\n"));
  EXPECT_NE(e.find("network.island"), std::string::npos) << e;
  EXPECT_NE(e.find("nothing drives it"), std::string::npos) << e;
}

TEST(NetworkScenario, AClutchThatCanNeverLoadIsRefused) {
  const std::string e = error_of(two_inertias("normal_force = { kind = \"step\", time_s = 1.5, after = 1 }\n"));
  EXPECT_NE(e.find("network.clutch"), std::string::npos) << e;
  EXPECT_NE(e.find("never rises above 0"), std::string::npos) << e;
}

TEST(NetworkScenario, AClutchJudgedOnNoShaftIsRefused) {
  const std::string e = error_of(
      two_inertias("judged_on = \"sprng\"\n[network.spring]\ntype = \"shaft\"\nfrom = \"wheel_side\"\nto = \"ground\"\n"
                   "stiffness_Nm_per_rad = 100\n"));
  EXPECT_NE(e.find("network.clutch"), std::string::npos) << e;
  EXPECT_NE(e.find("did you mean 'spring'"), std::string::npos) << e;
}

// Inputs beyond the shipped examples: each is one error naming where, never a crash or a run.
TEST(NetworkScenario, OutOfRangeAndMalformedInputsAreInputErrors) {
  const auto refused = [](const std::string& text, const std::string& what) {
    const std::string e = error_of(text);
    EXPECT_NE(e.find(what), std::string::npos) << "expected '" << what << "' in: " << e;
  };
  const std::string head = "[scenario]\ntype = \"network\"\nduration_s = 1.0\n";
  refused(head, "network");                     // no [network] table at all
  refused(head + "[network]\n", "no inertia");  // an empty network
  refused(head + "[network.a]\ntype = \"inertia\"\ninertia_kg_m2 = -1\n", "inertia_kg_m2");
  refused(head + "[network.a]\ntype = \"inertia\"\ninertia_kg_m2 = nan\n", "inertia_kg_m2");
  refused(head +
              "[network.a]\ntype = \"inertia\"\ninertia_kg_m2 = 1\nspeed_rpm = 10\n"
              "[network.g]\ntype = \"gear\"\ninput = \"a\"\noutput = \"a\"\nratio = 2\n",
          "joined to itself");
  refused(two_inertias("").replace(two_inertias("").find("mu = 0.1"), 8,
                                   "mu_table = { slip_rpm = [10, 0], mu = [0.1, 0.1] }"),
          "strictly increasing");
  refused(two_inertias("normal_force = { kind = \"sine\", amplitude = 1, frequency_Hz = 0 }\n"), "frequency_Hz");
  refused(two_inertias("normal_force = { kind = \"pulse\", high = 1, period_s = 0.1, width_s = 0.2 }\n"), "width_s");
  refused(two_inertias("normal_force = { kind = \"product\", factors = [{ value = 1 }] }\n"), "two factor");
  refused(two_inertias("normal_force = { kind = \"ramp\", to = 1 }\n"), "duration_s");
  refused(two_inertias("[network.tyre]\ntype = \"tyre\"\nwheel = \"wheel_side\"\nvehicle = \"engine_side\"\n"
                       "vertical_load_N = 4000\n"),
          "not a component of type \"vehicle\"");
  // A tyre's load and slip stiffness: one source each (components/tyre.hpp).
  const std::string car =
      "[network.car]\ntype = \"vehicle\"\nmass_kg = 1500\nwheel_radius_m = 0.3\n"
      "wheelbase_m = 2.5\nfront_axle_load_share = 0.6\ncg_height_m = 0.5\n";
  const std::string tyre = "[network.tyre]\ntype = \"tyre\"\nwheel = \"wheel_side\"\nvehicle = \"car\"\n";
  refused(two_inertias(car + tyre + "vertical_load_N = 4000\nslip_stiffness_N = 8e4\nslip_stiffness_per_load = 18\n"),
          "slip_stiffness_per_load': is an alternative to slip_stiffness_N");
  refused(two_inertias(car + tyre + "axle = \"rear\"\nvertical_load_N = 4000\n"),
          "vertical_load_N': is not for a tyre on an axle");
  refused(two_inertias(car + tyre), "vertical_load_N': is required for a tyre without an axle");
}

// [solver] radial_cells sets the rings of every wet clutch's thermal grid (as a scenario's
// [solver] does for its one clutch); a plain clutch has none. Out of range it names the key.
TEST(NetworkScenario, SolverRadialCellsSetEveryWetClutchsRings) {
  const std::string wet =
      "[network.wet]\ntype = \"clutch\"\nlaw = \"wet\"\nfrom = \"wheel_side\"\nto = \"ground\"\n"
      "max_force_N = 1000\n[network.wet.clutch]\nfluid = \"" +
      test::source_path("scenarios/fluids/lsc_fluid_c.toml") + "\"\nstart_temp_C = 40\n";
  const auto rings = [&](const std::string& solver) {
    const auto sc = load_network_scenario_text(two_inertias(wet + solver), "net.toml");
    for (const auto& k : sc.spec.clutches)
      if (k.name == "wet") return k.wet.clutch.thermal.radial_cells;
    return -1;
  };
  EXPECT_EQ(rings(""), 20);
  EXPECT_EQ(rings("[solver]\nradial_cells = 10\n"), 10);
  const std::string e = error_of(two_inertias(wet + "[solver]\nradial_cells = 1\n"));
  EXPECT_NE(e.find("solver.radial_cells"), std::string::npos) << e;
}

// Magnitudes far from the examples' (a 1e-6 kg m^2 pinion, a 1e4 kg m^2 flywheel, a 100:1 gear,
// 20000 rpm) still run and close their energy account: nothing in the path assumes a car's scale.
TEST(NetworkScenario, ExtremeMagnitudesRunAndCloseTheirEnergyAccount) {
  const auto sc = load_network_scenario_text(R"([scenario]
type = "network"
duration_s = 0.5
[network.pinion]
type = "inertia"
inertia_kg_m2 = 1e-6
speed_rpm = 20000
[network.wheel]
type = "inertia"
inertia_kg_m2 = 1e4
[network.reduction]
type = "gear"
input = "pinion"
output = "hub"
ratio = 100
[network.hub]
type = "inertia"
inertia_kg_m2 = 0
[network.clutch]
type = "clutch"
from = "hub"
to = "wheel"
mu = 0.1
geometry_factor_m = 0.5
max_force_N = 2e5
)",
                                             "extreme.toml");
  const auto run = studies::run_network(sc.spec);
  EXPECT_LT(std::abs(run.recording.find_scalar("mechanical_energy_relative_error")->value), 1e-6);
  // Momentum about the wheel: J_pinion r^2 w_hub0 = (J_pinion r^2 + J_wheel) w_end (massless hub).
  const double r = 100.0, w_hub0 = 20000.0 / r, j_ref = 1e-6 * r * r;
  EXPECT_NEAR(run.recording.find("wheel.speed_rpm")->values.back(), j_ref * w_hub0 / (j_ref + 1e4), 1e-9);
}

TEST(NetworkScenario, AnUnknownKeyNamesTheNearest) {
  const std::string e = error_of(two_inertias("peak_raito = 1.2\n"));
  EXPECT_NE(e.find("network.clutch.peak_raito"), std::string::npos) << e;
  EXPECT_NE(e.find("peak_ratio"), std::string::npos) << e;
}

TEST(NetworkScenario, WetOnlyKeysOnAPlainClutchAreRefused) {
  const std::string e = error_of(two_inertias("[network.clutch.clutch]\nfluid = \"x.toml\"\n"));
  EXPECT_NE(e.find("belongs to law = \"wet\""), std::string::npos) << e;
}

TEST(NetworkScenario, OtherCommandsSayWhyTheyCannot) {
  const auto dir = test::scratch_dir("network_refusal");
  test::write_file(dir / "net.toml", two_inertias(""));
  const auto r =
      test::run_cli("screen '" + test::source_path("scenarios/fluids/lsc_fluid_c.toml") + "' --rig net.toml", dir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("\"network\" scenarios"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "one line: " << r.err;
}

// modes: J1 = 0.5 kg m^2 on a shaft k = 2000 N m/rad to ground, J2 = 1.5 kg m^2 through a clutch.
// Slipping, J1 alone on the shaft: f = sqrt(k / J1) / 2 pi = 10.066 Hz (J2 a free rigid body, 0 Hz);
// stuck, both on the shaft: f = sqrt(k / (J1 + J2)) / 2 pi = 5.033 Hz.
TEST(NetworkScenario, ModesWithTheClutchSlippingAndStuck) {
  const auto dir = test::scratch_dir("network_modes");
  test::write_file(dir / "net.toml", R"([scenario]
type = "network"
duration_s = 1.0
[network.a]
type = "inertia"
inertia_kg_m2 = 0.5
speed_rpm = 100
[network.b]
type = "inertia"
inertia_kg_m2 = 1.5
[network.spring]
type = "shaft"
from = "a"
to = "ground"
stiffness_Nm_per_rad = 2000
[network.c]
type = "clutch"
from = "a"
to = "b"
mu = 0.1
geometry_factor_m = 0.1
max_force_N = 100
)");
  const auto r = test::run_cli("modes net.toml", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto slipping = r.out.find("Every clutch slipping:"), stuck = r.out.find("Every clutch stuck:");
  ASSERT_NE(slipping, std::string::npos) << r.out;
  ASSERT_NE(stuck, std::string::npos) << r.out;
  EXPECT_NE(r.out.substr(slipping, stuck - slipping).find("10.066"), std::string::npos) << r.out;
  EXPECT_NE(r.out.substr(stuck).find("5.033"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("shape:          a          b"), std::string::npos) << r.out;  // named by node
}

TEST(NetworkScenario, RunWritesChannelsNamedAfterTheComponents) {
  const auto dir = test::scratch_dir("network_run");
  test::write_file(dir / "net.toml", two_inertias(""));
  const auto r = test::run_cli("run net.toml -o out.h5", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("clutch (plain, engine_side -> wheel_side)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("locked from"), std::string::npos) << r.out;
  EXPECT_TRUE(std::filesystem::exists(dir / "out.h5"));
}

}  // namespace
}  // namespace shudder::io
