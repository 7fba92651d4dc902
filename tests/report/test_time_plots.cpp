// Building blocks of the time-history figures (report/time_plots.hpp) and of multi-panel images
// (report/gnuplot.hpp): the envelope keeps every slice's extremes in time order and is the
// series itself when it is not denser than the image; a slice holds exactly the points of its
// window; a figure of several panels draws every panel's title and label.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>

#include "report/gnuplot.hpp"
#include "report/time_plots.hpp"
#include "tests/support/cli.hpp"

using namespace shudder;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

namespace {

// A 378 Hz sine of amplitude 2 on an offset 5, sampled at 20 kHz for 2 s (40 000 points, ~756
// periods): what a shudder run's torque looks like to a 1000 px image.
report::Series shudder_like() {
  report::Series s;
  s.label = "sine";
  for (int i = 0; i < 40000; ++i) {
    const double t = i / 20000.0;
    s.x.push_back(t);
    s.y.push_back(5.0 + 2.0 * std::sin(2.0 * std::numbers::pi * 378.0 * t));
  }
  return s;
}

}  // namespace

TEST(TimePlots, EnvelopeKeepsEachSlicesExtremesInTimeOrder) {
  const report::Series s = shudder_like();
  const report::Series e = report::envelope(s, 1000);
  ASSERT_EQ(e.x.size(), 2000u);  // two points per slice
  EXPECT_EQ(e.label, "sine");
  for (std::size_t i = 1; i < e.x.size(); ++i) EXPECT_LE(e.x[i - 1], e.x[i]) << i;
  // Two neighbouring slices of 40 samples each (~1.5 periods) hold a whole period, so their
  // four points reach both extremes of the sine to within the sampling (53 samples a period:
  // 2 (1 − cos(π/53)) ≈ 0.0035): the outline 3 .. 7 is kept everywhere.
  for (std::size_t b = 0; b + 1 < 1000; ++b) {
    const double lo = std::min({e.y[2 * b], e.y[2 * b + 1], e.y[2 * b + 2], e.y[2 * b + 3]});
    const double hi = std::max({e.y[2 * b], e.y[2 * b + 1], e.y[2 * b + 2], e.y[2 * b + 3]});
    EXPECT_NEAR(lo, 3.0, 0.01) << "slices " << b << ", " << b + 1;
    EXPECT_NEAR(hi, 7.0, 0.01) << "slices " << b << ", " << b + 1;
  }
}

TEST(TimePlots, EnvelopeLeavesASparseSeriesAndMarksAnEmptySliceAsAGap) {
  report::Series s;
  for (int i = 0; i < 100; ++i) s.x.push_back(i), s.y.push_back(i % 7);
  const report::Series same = report::envelope(s, 25);  // 4 points per slice: unchanged
  EXPECT_EQ(same.x, s.x);
  EXPECT_EQ(same.y, s.y);
  for (int i = 20; i < 40; ++i) s.y[static_cast<std::size_t>(i)] = NAN;
  const report::Series e = report::envelope(s, 10);  // slices of 10: slices 2 and 3 empty
  ASSERT_EQ(e.x.size(), 2u * 8u + 2u);
  EXPECT_TRUE(std::isnan(e.y[4]));
  EXPECT_TRUE(std::isnan(e.y[5]));
}

TEST(TimePlots, SliceHoldsExactlyTheWindowsPoints) {
  const report::Series s = shudder_like();
  const report::Series d = report::slice(s, 0.5, 0.5 + 8.0 / 378.0);
  ASSERT_FALSE(d.x.empty());
  EXPECT_GE(d.x.front(), 0.5);
  EXPECT_LE(d.x.back(), 0.5 + 8.0 / 378.0);
  EXPECT_EQ(d.x.size(), 424u);  // samples 10000 .. 10423 at 20 kHz
  EXPECT_EQ(d.x.size(), d.y.size());
}

TEST(TimePlots, MultiPanelFigureDrawsEveryPanel) {
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) GTEST_SKIP() << "gnuplot not installed";
  const auto dir = test::scratch_dir("multiplot");
  report::Plot top, left, right;
  top.title = "overview panel";
  top.series.push_back(report::envelope(shudder_like(), 1500));
  left.title = "left detail";
  left.series.push_back(report::slice(shudder_like(), 0.5, 0.52));
  right.title = "right detail";
  right.series.push_back(report::slice(shudder_like(), 1.9, 1.92));
  right.series_y2.push_back(report::slice(shudder_like(), 1.9, 1.92));
  right.y2label = "second axis";
  report::MultiPlot f;
  f.title = "figure title";
  f.rows = {{top}, {left, right}};
  f.row_heights = {2.0, 1.0};
  report::write_multiplot((dir / "f.svg").string(), f);
  const std::string svg = test::slurp(dir / "f.svg");
  for (const char* text : {"figure title", "overview panel", "left detail", "right detail", "second axis"})
    EXPECT_THAT(svg, HasSubstr(text)) << text;
  report::write_multiplot((dir / "f.png").string(), f);
  EXPECT_GT(fs::file_size(dir / "f.png"), 1000u);
  EXPECT_FALSE(fs::exists(dir / "f.png.tmp"));
}
