// Time-history figures with slip panel and detail panels; see time_plots.hpp.
#include "report/time_plots.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/nan.hpp"
#include "io/input_error.hpp"
#include "report/plot_data.hpp"
#include "studies/recording_detection.hpp"

namespace shudder::report {

namespace {

using dynamics::Recording;
using dynamics::Signal;

constexpr std::size_t kEnvelopeBins = 1500;   // ~1.5 slices per pixel of the 1000 px image
constexpr double kDetailPeriods = 8.0;        // periods of the shudder frequency in a detail panel
constexpr double kPeriodsBeforeOnset = 1.5;   // of which before the onset: the last quiet cycles
constexpr double kLongestDetail = 1.0 / 3.0;  // of the record: a longer window is no zoom (the
                                              // whole-record panel shows those periods already)

/// What one time figure shows.
struct TimeChannels {
  std::string title;         // the figure's title, naming the channels
  std::string ylabel;        // the quantity's axis, with unit
  std::vector<Series> main;  // the quantity (upper panel, detail panels)
  std::vector<Series> slip;  // the sliding speed (own panel; right axis of the details); may be empty
  std::string caption;       // for index.html
};

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() > suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

/// A detail window [from, to] of kDetailPeriods periods at frequency f starting `before`
/// periods ahead of `at`, kept inside the record [t0, t1].
std::pair<double, double> window_from(double at, double before, double f, double t0, double t1) {
  const double len = std::min(kDetailPeriods / f, t1 - t0);
  const double from = std::clamp(at - before / f, t0, t1 - len);
  return {from, from + len};
}

/// A vertical marker pair at the window's edges across [lo, hi] (no legend entry).
Series window_marks(double from, double to, double lo, double hi) {
  Series s;
  s.x = {from, from, kNaN, to, to};
  s.y = {lo, hi, kNaN, lo, hi};
  s.rgb = "#9a9a9a";
  s.dash_type = 3;
  s.line_width = 1.0;
  return s;
}

/// Line-and-marker curves get about a dozen markers whatever their number of points.
void space_markers(std::vector<Series>& series) {
  for (auto& s : series)
    if (s.style == SeriesStyle::kLinesPoints) s.point_interval = std::max<int>(1, static_cast<int>(s.x.size() / 12));
}

/// The finite y range of `series`; {NaN, NaN} if none.
std::pair<double, double> y_range(const std::vector<Series>& series) {
  double lo = INFINITY, hi = -INFINITY;
  for (const auto& s : series)
    for (double y : s.y)
      if (std::isfinite(y)) lo = std::min(lo, y), hi = std::max(hi, y);
  return lo <= hi ? std::make_pair(lo, hi) : std::make_pair(kNaN, kNaN);
}

/// `s` over [from, to] with x in `scale` units (1e3: ms) after `from`.
Series detail_of(const Series& s, double from, double to, double scale) {
  Series d = slice(s, from, to);
  for (double& x : d.x) x = scale * (x - from);
  d.label.clear();
  return d;
}

/// One detail panel: the quantity over [from, to] and the slip on the right axis (grey,
/// dashed); time from the window's start, in ms for windows under a second (seconds with four
/// digits would crowd the tics).
Plot detail_panel(const TimeChannels& ch, const std::string& title, double from, double to) {
  const bool ms = to - from < 1.0;
  const double scale = ms ? 1e3 : 1.0;
  Plot p;
  p.title = title;
  p.xlabel = "time − " + plot_number("%.5g", from) + (ms ? " s [ms]" : " s [s]");
  p.ylabel = ch.ylabel;
  for (const auto& s : ch.main) {
    Series d = detail_of(s, from, to, scale);
    if (d.x.size() >= 2) p.series.push_back(std::move(d));
  }
  for (const auto& s : ch.slip) {
    Series d = detail_of(s, from, to, scale);
    d.rgb = "#7f7f7f";
    d.dash_type = 2;
    d.line_width = 1.0;
    if (d.x.size() >= 2) p.series_y2.push_back(std::move(d));
  }
  if (!p.series_y2.empty()) p.y2label = "slip [rpm] (grey, dashed)";
  space_markers(p.series);
  p.x_min = 0.0;
  p.x_max = scale * (to - from);
  return p;
}

MultiPlot time_figure(const Recording& rec, TimeChannels ch) {
  const std::optional<analysis::ShudderResult> det = detect(rec);
  MultiPlot f;
  f.caption = ch.caption;
  f.width_px = 1000;

  Plot overview;
  overview.title = ch.title;
  overview.xlabel = "time [s]";
  overview.ylabel = ch.ylabel;
  for (const auto& s : ch.main) overview.series.push_back(envelope(s, kEnvelopeBins));
  space_markers(overview.series);

  Plot slip;
  // One slip channel is named by the axis, leaving the panel's height to the curve.
  slip.xlabel = "time [s]";
  slip.ylabel = ch.slip.size() == 1 ? ch.slip.front().label + " [rpm]" : "slip [rpm]";
  for (const auto& s : ch.slip) {
    slip.series.push_back(envelope(s, kEnvelopeBins));
    slip.series.back().line_width = 1.2;
    if (ch.slip.size() == 1) slip.series.back().label.clear();
  }

  // Detail windows: around the onset (or the oscillating part's start) and at its end.
  std::vector<Plot> details;
  const Signal* time = rec.find("time_s");
  const double span = time && time->values.size() > 2 ? time->values.back() - time->values.front() : 0.0;
  if (oscillating(det) && span > 0 && kDetailPeriods / det->frequency_Hz <= kLongestDetail * span) {
    const double t0 = time->values.front(), t1 = time->values.back(), fd = det->frequency_Hz;
    const double onset = std::isfinite(det->onset_time_s) ? det->onset_time_s : det->oscillating_from_s;
    const double end = std::isfinite(det->oscillating_to_s) && det->oscillating_to_s > t0 ? det->oscillating_to_s : t1;
    const auto [a0, a1] = window_from(onset, kPeriodsBeforeOnset, fd, t0, t1);
    const auto [b0, b1] = window_from(end, kDetailPeriods, fd, t0, t1);
    const std::string periods = plot_number("%.0f", kDetailPeriods) + " periods of " + plot_number("%.4g", fd) + " Hz";
    details.push_back(
        detail_panel(ch, "onset detail (onset " + plot_number("%.3g", onset) + " s): " + periods, a0, a1));
    details.push_back(detail_panel(
        ch, "end detail (" + plot_number("%.4g", b0) + "–" + plot_number("%.4g", b1) + " s): " + periods, b0, b1));
    // The windows marked on the overview (dotted grey), so the reader sees where they come from.
    const auto [lo, hi] = y_range(overview.series);
    if (std::isfinite(lo)) {
      overview.series.push_back(window_marks(a0, a1, lo, hi));
      overview.series.push_back(window_marks(b0, b1, lo, hi));
    }
    f.caption += " The lower panels zoom into " + periods + " at the onset (" + plot_number("%.4g", a0) + "–" +
                 plot_number("%.4g", a1) + " s) and at the end of the oscillation (" + plot_number("%.4g", b0) + "–" +
                 plot_number("%.4g", b1) + " s), marked by dotted lines above; the shudder detector found " +
                 verdict_text(det->verdict) + " at " + plot_number("%.4g", fd) + " Hz.";
  }

  f.rows.push_back({overview});
  f.row_heights.push_back(3.0);
  if (!slip.series.empty()) {
    f.rows.push_back({slip});
    f.row_heights.push_back(1.8);
  }
  if (!details.empty()) {
    f.rows.push_back(details);
    f.row_heights.push_back(2.6);
  }
  f.height_px = 420 + (slip.series.empty() ? 0 : 200) + (details.empty() ? 0 : 330);
  return f;
}

Series line_of(const Signal& t, const Signal& y, std::string label, const std::string& rgb, int dash, double width) {
  Series s = series_of(t, y, std::move(label));
  s.rgb = rgb;
  s.dash_type = dash;
  s.line_width = width;
  return s;
}

/// A torque (solid blue), a second one if recorded (dashed red) and the slip (own panel); the
/// title holds the channels' names.
TimeChannels torque_pair(const Recording& rec, const Signal& t, const Signal& torque, const char* label,
                         const char* second, const char* second_label, const Signal* slip) {
  TimeChannels ch;
  ch.ylabel = "torque [N m]";
  ch.main.push_back(line_of(t, torque, label, "#1f77b4", 1, 1.2));
  ch.title = torque.name;
  if (const Signal* other = rec.find(second)) {
    ch.main.push_back(line_of(t, *other, second_label, "#d62728", 2, 1.2));
    ch.title += ", " + other->name;
  }
  if (slip) {
    ch.slip.push_back(line_of(t, *slip, slip->name, "#4d4d4d", 1, 1.2));
    ch.title += "; " + slip->name + " below";
  }
  return ch;
}

// A network run: every clutch's torque (the channels CLUTCH.torque_Nm beside CLUTCH.slip_rpm).
MultiPlot network_torque_plot(const Recording& rec, const std::string& name, const std::string& source) {
  const Signal& t = require_signal(rec, "time_s", source, "torque");
  TimeChannels ch;
  ch.ylabel = "torque [N m]";
  std::string names;
  for (const auto& s : rec.signals)
    if (ends_with(s.name, ".slip_rpm"))
      if (const Signal* torque = rec.find(s.name.substr(0, s.name.size() - 9) + ".torque_Nm")) {
        ch.main.push_back(series_of(t, *torque, torque->name));
        ch.main.back().line_width = 1.2;
        ch.slip.push_back(series_of(t, s, s.name));
        ch.slip.back().line_width = 1.2;
        names += (names.empty() ? "" : ", ") + torque->name;
      }
  ch.title = name + ": clutch torques (" + names + ")";
  ch.caption = "Every clutch's friction torque against time; their slip speeds in the panel below.";
  return time_figure(rec, ch);
}

}  // namespace

Series envelope(const Series& s, std::size_t bins) {
  const std::size_t n = s.x.size();
  if (bins == 0 || n <= 4 * bins) return s;
  Series out = s;
  out.x.clear();
  out.y.clear();
  for (std::size_t b = 0; b < bins; ++b) {
    const std::size_t from = b * n / bins, to = (b + 1) * n / bins;
    std::size_t lo = n, hi = n;
    for (std::size_t i = from; i < to; ++i) {
      if (!std::isfinite(s.y[i]) || !std::isfinite(s.x[i])) continue;
      if (lo == n || s.y[i] < s.y[lo]) lo = i;
      if (hi == n || s.y[i] > s.y[hi]) hi = i;
    }
    if (lo == n) {
      out.x.push_back(kNaN);
      out.y.push_back(kNaN);
      continue;
    }
    for (std::size_t i : {std::min(lo, hi), std::max(lo, hi)}) {
      out.x.push_back(s.x[i]);
      out.y.push_back(s.y[i]);
    }
  }
  return out;
}

Series slice(const Series& s, double from_x, double to_x) {
  Series out = s;
  out.x.clear();
  out.y.clear();
  for (std::size_t i = 0; i < s.x.size(); ++i)
    if (s.x[i] >= from_x && s.x[i] <= to_x) {
      out.x.push_back(s.x[i]);
      out.y.push_back(s.y[i]);
    }
  return out;
}

MultiPlot torque_plot(const Recording& rec, const std::string& name, const std::string& source) {
  if (studies::network_verdict_clutch(rec)) return network_torque_plot(rec, name, source);
  const Signal& t = require_signal(rec, "time_s", source, "torque");
  const Signal& torque = require_signal(rec, "torque_Nm", source, "torque");
  // The sliding speed explains the torque's shape (ramps, breakaway): its own panel.
  const Signal* speed = rec.find("slip_rpm");
  if (!speed) speed = rec.find("speed_rpm");
  TimeChannels ch = torque_pair(rec, t, torque, "torque_Nm: measured torque (torque cell)", "clutch_torque_Nm",
                                "clutch_torque_Nm: friction torque of the clutch (dashed)", speed);
  ch.title = name + ": torque (" + ch.title + ")";
  ch.caption =
      "The torque cell's torque and the clutch's friction torque against time over the whole record"
      " (a record denser than the image is drawn as its envelope); the sliding speed in the panel below.";
  return time_figure(rec, ch);
}

MultiPlot coupling_plot(const Recording& rec, const std::string& name, const std::string& source) {
  const Signal& t = require_signal(rec, "time_s", source, "coupling");
  const Signal& torque = require_signal(rec, "coupling_torque_Nm", source, "coupling");
  TimeChannels ch =
      torque_pair(rec, t, torque, "coupling_torque_Nm: torque through the coupling", "rear_axle_torque_Nm",
                  "rear_axle_torque_Nm: rear half-shafts (dashed)", rec.find("coupling_slip_rpm"));
  ch.title = name + ": Haldex coupling (" + ch.title + ")";
  ch.caption =
      "The torque through the Haldex coupling and the rear half-shafts' torque against time; the"
      " coupling's slip, which pumps its pressure, in the panel below (docs/driveline.md).";
  return time_figure(rec, ch);
}

MultiPlot temperature_plot(const Recording& rec, const std::string& name, const std::string& source) {
  const Signal& t = require_signal(rec, "time_s", source, "temperature");
  // Colour, dash and marker each tell the channels apart, also where two lie on each other
  // (the thermocouple and the IR pyrometer often read within a tenth of a degree).
  struct Channel {
    const char* signal;
    const char* label;
    const char* rgb;
    int dash;
    int point;
    double width;
  };
  static constexpr Channel kChannels[] = {
      {"temp_C", "temp_C: separator thermocouple (solid, circles)", "#1f77b4", 1, 6, 2.5},
      {"ir_temp_C", "ir_temp_C: IR pyrometer (dashed, triangles)", "#ff7f0e", 2, 8, 1.8},
      {"sump_temp_C", "sump_temp_C: oil sump (dash-dot, squares)", "#2ca02c", 4, 4, 1.8},
      {"interface_max_temp_C", "interface_max_temp_C: hottest point of the friction interface (dotted, crosses)",
       "#d62728", 3, 2, 1.8}};
  TimeChannels ch;
  ch.ylabel = "temperature [°C]";
  std::string names;
  const Signal* thermocouple = rec.find("temp_C");
  for (const auto& c : kChannels) {
    const Signal* s = rec.find(c.signal);
    if (!s) continue;
    std::string label = c.label;
    // Say so when the pyrometer lies on the thermocouple: the legend alone cannot show it.
    if (thermocouple && s != thermocouple && std::string(c.signal) == "ir_temp_C") {
      double gap = 0.0;
      for (std::size_t i = 0; i < s->values.size() && i < thermocouple->values.size(); ++i)
        if (std::isfinite(s->values[i]) && std::isfinite(thermocouple->values[i]))
          gap = std::max(gap, std::abs(s->values[i] - thermocouple->values[i]));
      label += "; within " + plot_number("%.2g", gap) + " °C of temp_C";
    }
    Series line = line_of(t, *s, label, c.rgb, c.dash, c.width);
    line.style = SeriesStyle::kLinesPoints;
    line.point_type = c.point;
    line.point_size = 1.3;
    ch.main.push_back(std::move(line));
    names += (names.empty() ? "" : ", ") + std::string(c.signal);
  }
  // A network's wet clutches: each one's hottest interface point (CLUTCH.interface_max_temp_C).
  for (const auto& s : rec.signals)
    if (ends_with(s.name, ".interface_max_temp_C")) {
      ch.main.push_back(series_of(t, s, s.name));
      names += (names.empty() ? "" : ", ") + s.name;
    }
  if (ch.main.empty())
    throw io::InputError(source, 0, "",
                         "no temperature signals (temp_C, ir_temp_C, sump_temp_C, "
                         "interface_max_temp_C): the temperature plot needs at least one");
  ch.title = name + ": temperatures (" + names + ")";
  ch.caption =
      "The rig's thermometers against time: each channel has its own colour, dash pattern and marker,"
      " so the thermocouple and the IR pyrometer stay apart where they read alike.";
  return time_figure(rec, ch);
}

}  // namespace shudder::report
