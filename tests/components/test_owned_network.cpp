// components::OwnedNetwork: a spec and its built network kept together, and the clutch inputs
// it hands out only where a clutch has them.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "components/network_builder.hpp"
#include "network_helpers.hpp"

namespace shudder::components {
namespace {

using test::inertia;
using test::plain_clutch;

// A built network refers to its spec (BuiltClutch::spec, the clutch names); the owned copy must
// serve after the caller's spec is gone.
OwnedNetwork two_inertias_and_a_plain_clutch() {
  NetworkSpec spec;
  spec.inertias = {inertia("a", 0.5, 10.0), inertia("b", 1.5)};
  spec.clutches = {plain_clutch("launch", "a", "b", 60.0)};
  spec.settings.duration_s = 1.0;
  return OwnedNetwork(std::move(spec));
}

TEST(OwnedNetwork, KeepsItsSpecForTheNetworkBuiltFromIt) {
  const OwnedNetwork owned = two_inertias_and_a_plain_clutch();
  ASSERT_EQ(owned.built().clutches.size(), 1u);
  EXPECT_EQ(owned.built().clutches[0].name(), "launch");
  EXPECT_EQ(&owned.built().clutches[0].spec->name, &owned.spec().clutches[0].name);
  ASSERT_EQ(owned.network().inertias().size(), 2u);
  EXPECT_DOUBLE_EQ(owned.network().inertias()[1].inertia_kg_m2, 1.5);
}

// The message of the std::invalid_argument `ask` throws ("" if it throws none).
template <typename F>
std::string refusal(F ask) {
  try {
    ask();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(OwnedNetwork, APlainClutchHasNoHeldInputsNorValveCommand) {
  const OwnedNetwork owned = two_inertias_and_a_plain_clutch();
  EXPECT_NE(refusal([&] { owned.clutch_context(0); }).find("'launch'"), std::string::npos);
  EXPECT_NE(refusal([&] { owned.command(0); }).find("not a Haldex coupling"), std::string::npos);
}

TEST(OwnedNetwork, AClutchIndexBeyondTheNetworkIsRefused) {
  const OwnedNetwork owned = two_inertias_and_a_plain_clutch();
  EXPECT_NE(refusal([&] { owned.clutch_context(1); }).find("1 clutches"), std::string::npos);
}

}  // namespace
}  // namespace shudder::components
