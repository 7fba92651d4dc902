// A run's result blocks (dynamics::ResultBlock, e.g. the verdict) through the HDF5 writer and
// reader and the verdict JSON (io/verdict_json.hpp).
//
// Old behaviour: the Recording had no result blocks and the writer nothing to put under
// /analysis beyond the summary and maps, so no verdict could be stored or read back; there was
// no verdict JSON. These tests do not compile on the old code, and the old reader skipped any
// group under /analysis without map attributes.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "io/hdf5_run.hpp"
#include "io/input_error.hpp"
#include "io/verdict_json.hpp"
#include "tests/support/cli.hpp"
#include "tests/support/json.hpp"

namespace fs = std::filesystem;
using shudder::dynamics::Recording;
using shudder::dynamics::ResultBlock;
using shudder::io::InputError;
using testing::HasSubstr;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

fs::path scratch(const std::string& name) {
  const auto dir = fs::temp_directory_path() / ("shudder_verdict_io_" + std::to_string(::getpid()) + "_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

ResultBlock sample_block() {
  ResultBlock b;
  b.name = "verdict";
  b.description = "a test block";
  b.texts = {{"verdict", "stick_slip"}, {"prediction", "not predicted: \"quoted\" \\ and\ttab"}};
  b.scalars = {{"verdict_code", "1", 2.0},
               {"frequency_Hz", "Hz", 210.70123456789},
               {"onset_time_s", "s", kNaN},
               {"predicted_margin_per_s", "1/s", -44.1}};
  return b;
}

Recording with_block(const ResultBlock& b) {
  Recording rec;
  rec.add_signal("time_s", "s").values = {0.0, 0.1};
  rec.scalars = {{"peak_interface_temp_C", "degC", 69.2}};
  rec.blocks = {b};
  return rec;
}

TEST(VerdictOutput, ResultBlockRoundTripsThroughHdf5BitForBit) {
  const auto dir = scratch("round_trip");
  const std::string path = (dir / "r.h5").string();
  const long open_before = shudder::io::detail::open_hdf5_identifiers();
  shudder::io::write_run_hdf5(path, with_block(sample_block()), "scenario text");
  const Recording back = shudder::io::read_run_hdf5(path);
  EXPECT_EQ(shudder::io::detail::open_hdf5_identifiers(), open_before);  // no handle leaks
  // The summary is not a block; the verdict group is, with every text and scalar.
  ASSERT_EQ(back.blocks.size(), 1u);
  EXPECT_EQ(back.scalars.size(), 1u);
  const ResultBlock& b = back.blocks.front();
  EXPECT_EQ(b.name, "verdict");
  EXPECT_EQ(b.description, "a test block");
  ASSERT_EQ(b.texts.size(), 2u);  // in name order
  EXPECT_EQ(b.find_text("verdict")->value, "stick_slip");
  EXPECT_EQ(b.find_text("prediction")->value, sample_block().texts[1].value);
  ASSERT_EQ(b.scalars.size(), 4u);
  for (const auto& s : sample_block().scalars) {
    const auto* r = b.find_scalar(s.name);
    ASSERT_NE(r, nullptr) << s.name;
    EXPECT_EQ(r->units, s.units);
    if (std::isnan(s.value))
      EXPECT_TRUE(std::isnan(r->value)) << s.name;
    else
      EXPECT_EQ(r->value, s.value) << s.name;  // float64 both ways: exact
  }
  fs::remove_all(dir);
}

TEST(VerdictOutput, BlockNamesMustBeFreeAndUnique) {
  const auto dir = scratch("names");
  const std::string path = (dir / "r.h5").string();
  const auto rejects = [&](const ResultBlock& b, const std::string& what) {
    try {
      shudder::io::write_run_hdf5(path, with_block(b), "");
      ADD_FAILURE() << "accepted: " << what;
    } catch (const InputError& e) {
      EXPECT_THAT(e.what(), HasSubstr(what));
    }
    EXPECT_FALSE(fs::exists(path));
  };
  ResultBlock summary = sample_block();
  summary.name = "summary";
  rejects(summary, "taken by the summary or a map");
  ResultBlock twice = sample_block();
  twice.scalars.push_back(twice.scalars.front());
  rejects(twice, "scalar name 'verdict_code' must be non-empty, unique");
  ResultBlock description = sample_block();
  description.texts.push_back({"description", "x"});
  rejects(description, "text name 'description' must be non-empty, unique and not 'description'");
  fs::remove_all(dir);
}

TEST(VerdictOutput, JsonIsStrictWithEveryKeyAndNullForUndefined) {
  const auto j = shudder::test::parse(shudder::io::verdict_json(sample_block()));
  EXPECT_EQ(j["format"].str(), "shudder-verdict/1");
  EXPECT_EQ(j["verdict"].str(), "stick_slip");
  EXPECT_EQ(j["prediction"].str(), "not predicted: \"quoted\" \\ and\ttab");
  EXPECT_EQ(j["verdict_code"].num(), 2.0);
  EXPECT_NEAR(j["frequency_Hz"].num(), 210.70123456789, 1e-7);  // 10 significant digits
  EXPECT_TRUE(j["onset_time_s"].is_null());                     // NaN: undefined
  EXPECT_EQ(j["predicted_margin_per_s"].num(), -44.1);
  EXPECT_EQ(j.members.size(), 7u);  // format + 2 texts + 4 scalars
}

TEST(VerdictOutput, JsonWriteIsAtomicAndNamesAnUnwritablePath) {
  const auto dir = scratch("json_write");
  const std::string path = (dir / "verdict.json").string();
  shudder::io::write_verdict_json(sample_block(), path);
  EXPECT_NO_THROW(shudder::test::parse(shudder::test::slurp(path)));
  EXPECT_FALSE(fs::exists(path + ".tmp"));
  try {
    shudder::io::write_verdict_json(sample_block(), (dir / "no_such_dir" / "v.json").string());
    ADD_FAILURE() << "wrote into a missing directory";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("no_such_dir/v.json"));
  }
  fs::remove_all(dir);
}

}  // namespace
