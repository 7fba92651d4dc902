// Plot builders for `shudder plot` and the report directories; see plots.hpp and docs/plots.md.
#include "report/plots.hpp"

#include "report/plot_data.hpp"
#include "report/text_format.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "analysis/shudder_detection.hpp"
#include "analysis/spectrum.hpp"
#include "studies/recording_detection.hpp"
#include "studies/run_verdict.hpp"
#include "io/atomic_file.hpp"
#include "io/hdf5_run.hpp"
#include "io/input_error.hpp"
#include "io/verdict_json.hpp"
#include "core/nan.hpp"

namespace shudder::report {

namespace {

namespace fs = std::filesystem;
using dynamics::Recording;
using dynamics::Signal;

}  // namespace

const std::vector<std::string>& plot_kind_names() {
  static const std::vector<std::string> names = {"torque",        "temperature", "spectrum", "spectrogram",
                                                 "stability_map", "sweep",       "coupling"};
  return names;
}

std::optional<PlotKind> parse_plot_kind(std::string_view name) {
  const auto& names = plot_kind_names();
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return static_cast<PlotKind>(i);
  return std::nullopt;
}

std::string scenario_name(const std::string& scenario_text, const std::string& fallback) {
  try {
    const toml::table t = toml::parse(scenario_text);
    if (auto name = t["scenario"]["name"].value<std::string>(); name && !name->empty()) return *name;
  } catch (const toml::parse_error&) {
    // Not TOML (or none stored): the file name stands in.
  }
  return fallback;
}

// ---- spectra -----------------------------------------------------------------------------

namespace {

/// Hann amplitude spectrum of x[from, to) less its mean, as a curve up to f_max (zeros left out:
/// the axis is logarithmic).
analysis::Spectrum part_spectrum(const std::vector<double>& x, std::size_t from, std::size_t to, double fs) {
  std::vector<double> part(x.begin() + static_cast<long>(from), x.begin() + static_cast<long>(to));
  const double mean = std::accumulate(part.begin(), part.end(), 0.0) / static_cast<double>(part.size());
  for (double& v : part) v -= mean;
  const analysis::SpectralAnalyzer spectra;
  return spectra.amplitude_spectrum(part, fs, analysis::Window::kHann);
}

Series spectrum_curve(const analysis::Spectrum& sp, double f_max, std::string label) {
  Series s;
  s.label = std::move(label);
  for (std::size_t k = 0; k < sp.frequency_Hz.size() && sp.frequency_Hz[k] <= f_max; ++k) {
    s.x.push_back(sp.frequency_Hz[k]);
    s.y.push_back(sp.amplitude[k] > 0 ? sp.amplitude[k] : kNaN);
  }
  return s;
}

/// The interpolated peak of `sp` within ±10 % of f; nothing when no bin lies there.
std::optional<analysis::Peak> peak_near(const analysis::Spectrum& sp, double f, double fs) {
  try {
    return analysis::find_peak(sp, 0.9 * f, std::min(1.1 * f, 0.5 * fs));
  } catch (const std::invalid_argument&) {
    return std::nullopt;
  }
}

// The spectrum's amplitude at `f`, linear between the bins around it; nullopt outside its bins.
std::optional<double> amplitude_at(const analysis::Spectrum& sp, double f) {
  const auto& fr = sp.frequency_Hz;
  const auto above = std::upper_bound(fr.begin(), fr.end(), f);
  if (above == fr.begin() || above == fr.end()) return std::nullopt;
  const std::size_t k = static_cast<std::size_t>(above - fr.begin());
  const double w = (f - fr[k - 1]) / (fr[k] - fr[k - 1]);
  return (1.0 - w) * sp.amplitude[k - 1] + w * sp.amplitude[k];
}

}  // namespace

Plot spectrum_plot(const Recording& rec, const std::string& name, const std::string& source) {
  const Signal& t = require_signal(rec, "time_s", source, "spectrum");
  // The torque the run was judged on: the torque cell, or a driveline's coupling.
  const std::string_view torque_name = studies::judged_torque_signal(rec);
  const Signal& torque = require_signal(rec, torque_name, source, "spectrum");
  const double fs = sample_rate_Hz(t, 64, source, "spectrum");
  const std::size_t n = t.values.size();

  const auto det = detect(rec);
  const double f_focus = focus_frequency_Hz(det);
  const bool shudder = oscillating(det);
  // Up to the third harmonic of a detected shudder; else the detector's whole band.
  const double f_max = shudder ? std::min(0.5 * fs, 3.0 * f_focus) : std::min(0.5 * fs, 2000.0);
  const analysis::Spectrum whole = part_spectrum(torque.values, 0, n, fs);

  // The oscillating part the detector measured (its definition 4): where the oscillation has
  // grown to within a factor 10 of its largest. A shorter window than the record when the run
  // is quiet before the onset.
  std::size_t from = 0, to = n;
  if (shudder) {
    const auto& tv = t.values;
    from = static_cast<std::size_t>(std::lower_bound(tv.begin(), tv.end(), det->oscillating_from_s) - tv.begin());
    to = static_cast<std::size_t>(std::upper_bound(tv.begin(), tv.end(), det->oscillating_to_s) - tv.begin());
    if (to < from + 64 || (from == 0 && to == n)) from = 0, to = n;
  }
  const bool part = from > 0 || to < n;

  Plot p;
  p.title = name + ": amplitude spectrum of " + std::string(torque_name) + " (Hann window, bin " +
            plot_number("%.3g", whole.bin_width_Hz) + " Hz over the whole record of " +
            duration_text(t.values.back() - t.values.front()) + ")";
  p.xlabel = "frequency [Hz]";
  p.ylabel = "torque amplitude [N m]";
  p.log_y = true;
  p.x_min = 0.0;
  p.x_max = f_max;
  Series w =
      spectrum_curve(whole, f_max,
                     std::string(torque_name) + " less its mean, whole record " +
                         plot_number("%.4g", t.values.front()) + "–" + plot_number("%.4g", t.values.back()) + " s");
  w.line_width = part ? 1.0 : 1.5;
  if (part) w.rgb = "#9a9a9a";
  p.series.push_back(std::move(w));
  std::optional<analysis::Spectrum> osc;
  if (part) {
    osc = part_spectrum(torque.values, from, to, fs);
    Series o = spectrum_curve(*osc, f_max,
                              "oscillating part " + plot_number("%.4g", t.values[from]) + "–" +
                                  plot_number("%.4g", t.values[to - 1]) + " s (the detector's window)");
    o.rgb = "#1f77b4";
    o.line_width = 1.5;
    p.series.push_back(std::move(o));
  }

  if (!(std::isfinite(f_focus) && f_focus < 0.5 * fs)) return p;
  if (!shudder) {
    // No shudder: the detector's own figures for its strongest oscillation (the frequency and
    // amplitude the summary prints), marked on the whole record's curve at that frequency. The
    // curve's own peak nearby may sit elsewhere: the detector judged its window (a network
    // clutch's loaded part of the run), the curve is the whole record.
    const auto level = amplitude_at(whole, f_focus);
    if (!level) return p;
    Series mark;
    mark.label = "strongest oscillation the detector examined (no shudder detected)";
    mark.x = {f_focus};
    mark.y = {*level};
    mark.style = SeriesStyle::kPoints;
    mark.point_type = 6;
    mark.point_size = 2.0;
    mark.color = 1;
    p.series.push_back(std::move(mark));
    // Above the threshold yet none: the rule that a judder lasts (a driveline's or a network
    // clutch's) set the oscillation aside as a transient.
    const bool transient = det->amplitude_Nm >= det->threshold_Nm;
    p.labels.push_back({f_focus, *level,
                        "no shudder: largest oscillation " + plot_number("%.3g", det->amplitude_Nm) + " N m at " +
                            plot_number("%.3g", f_focus) + " Hz\n" +
                            (transient ? "above the threshold " + plot_number("%.3g", det->threshold_Nm) +
                                             " N m but not sustained (a transient)"
                                       : "under the threshold " + plot_number("%.3g", det->threshold_Nm) + " N m")});
    p.caption =
        "Amplitude spectrum of the judged torque over the whole record; the open circle marks the frequency"
        " of the strongest oscillation the shudder detector examined, which stayed under its threshold or"
        " did not last. Its amplitude is the detector's (half the peak-to-peak of the torque less its"
        " one-period moving mean, analysis/shudder_detection.hpp, definition 6), the curve's the"
        " fundamental's over the whole record.";
    return p;
  }
  // The detected peak, interpolated in the spectrum the detector's frequency comes from.
  const auto peak = peak_near(osc ? *osc : whole, f_focus, fs);
  if (!peak) return p;  // no bin in the band (record too short for that frequency)
  const auto whole_peak = peak_near(whole, f_focus, fs);
  Series mark;
  mark.label = "detected shudder frequency";
  mark.x = {peak->frequency_Hz};
  mark.y = {peak->amplitude};
  mark.style = SeriesStyle::kPoints;
  mark.point_type = 7;
  mark.point_size = 2.0;
  mark.color = 1;
  p.series.push_back(std::move(mark));
  const std::string detector = plot_number("%.3g", det->amplitude_Nm);
  p.labels.push_back(
      {peak->frequency_Hz, peak->amplitude,
       verdict_text(det->verdict) + " at " + plot_number("%.1f", det->frequency_Hz) + " Hz\nfundamental " +
           plot_number("%.3g", peak->amplitude) + " N m" +
           (part && whole_peak ? " (whole record: " + plot_number("%.3g", whole_peak->amplitude) + " N m)" : "") +
           "\ndetector amplitude " + detector + " N m (half peak-to-peak)"});
  // Why the numbers differ, in the page's caption.
  p.caption =
      "The spectrum's peak is the amplitude of the oscillation's fundamental, averaged over the analysed "
      "window with the Hann window's weight (largest mid-window). Over the whole record that average "
      "includes the quiet time before the onset and the growth, so it reads lower" +
      (whole_peak ? " (" + plot_number("%.3g", whole_peak->amplitude) + " N m)" : std::string()) +
      "; over the oscillating part the detector measured it reads " + plot_number("%.3g", peak->amplitude) +
      " N m. The detector's amplitude, " + detector +
      " N m, is half the peak-to-peak of the torque less its one-period moving mean in the saturated "
      "oscillation (analysis/shudder_detection.hpp, definition 6): it includes the harmonics and any "
      "remaining growth or beating, so it is at or above the fundamental's amplitude.";
  return p;
}

Plot spectrogram_plot(const Recording& rec, const std::string& name, const std::string& source) {
  const Signal& t = require_signal(rec, "time_s", source, "spectrogram");
  const Signal& torque = require_signal(rec, studies::judged_torque_signal(rec), source, "spectrogram");
  const double fs = sample_rate_Hz(t, 256, source, "spectrogram");
  const std::size_t n = t.values.size();

  // Centre frequency: the detected one, else the strongest Welch peak in 5 Hz .. 0.45 fs.
  const auto det = detect(rec);
  double f = focus_frequency_Hz(det);
  if (!(f > 0 && f < 0.45 * fs)) {
    const analysis::SpectralAnalyzer spectra;
    analysis::WelchSettings w;
    w.segment_length = 1;
    while (w.segment_length * 2 <= n / 4) w.segment_length *= 2;
    try {
      const analysis::Psd psd = spectra.welch_psd(torque.values, fs, w);
      f = analysis::peak_frequency_Hz(psd, analysis::Window::kHann, std::min(5.0, 0.1 * fs), 0.45 * fs);
    } catch (const std::invalid_argument&) {
      f = kNaN;
    }
    if (!(f > 0 && f < 0.5 * fs))
      throw io::InputError(source, 0, "", "no spectral peak in the torque to centre a spectrogram on");
  }

  // Frames of ~16 periods (a power of two, at most a quarter of the record); ~8 frames per
  // frame length, at most ~600 frames.
  std::size_t len = 16;
  while (static_cast<double>(len) < 16.0 * fs / f && len * 2 <= n / 4) len *= 2;
  analysis::SpectrogramSettings cfg;
  cfg.segment_length = len;
  cfg.hop = std::max<std::size_t>({1, len / 8, (n - len) / 600});
  const analysis::SpectralAnalyzer spectra;
  const analysis::Spectrogram sg = spectra.spectrogram(torque.values, fs, cfg, t.values.front());

  const double f_lo = 0.5 * f, f_hi = std::min(2.5 * f, 0.5 * fs);
  std::vector<std::size_t> bins;
  for (std::size_t k = 0; k < sg.frequency_Hz.size(); ++k)
    if (sg.frequency_Hz[k] >= f_lo && sg.frequency_Hz[k] <= f_hi) bins.push_back(k);
  if (bins.size() < 2 || sg.times_s.size() < 2)
    throw io::InputError(source, 0, "",
                         "the record (" + std::to_string(n) + " samples) is too short for a spectrogram around " +
                             plot_number("%.4g", f) + " Hz");

  ColorMap map;
  map.x = sg.times_s;
  for (std::size_t k : bins) map.y.push_back(sg.frequency_Hz[k]);
  double top = -INFINITY;
  for (std::size_t i = 0; i < sg.times_s.size(); ++i)
    for (std::size_t k : bins) {
      const double power = sg.power(static_cast<long>(i), static_cast<long>(k));
      const double db = 10.0 * std::log10(std::max(power, 1e-300));
      map.values.push_back(db);
      top = std::max(top, db);
    }
  map.min = top - 60.0;  // 60 dB of dynamic range: growth from the floor to the limit cycle
  map.max = top;
  map.label = "torque PSD [dB re 1 (N m)²/Hz]";

  Plot p;
  p.title = name + ": spectrogram of " + torque.name + " (frames of " + duration_text(static_cast<double>(len) / fs) +
            " = " + plot_number("%.3g", static_cast<double>(len) * f / fs) + " periods of " + plot_number("%.4g", f) +
            " Hz, Hann)";
  p.caption = "Short-time power spectral density of " + torque.name +
              " in dB over time and frequency, in the band "
              "0.5–2.5 times the dominant frequency (white dashed line); the orange line marks the detected onset. "
              "Each column is one frame of " +
              duration_text(static_cast<double>(len) / fs) + ".";
  p.xlabel = "time [s] (frame centre)";
  p.ylabel = "frequency [Hz]";
  p.map = std::move(map);
  const double t0 = p.map.x.front(), t1 = p.map.x.back();
  if (f >= f_lo && f <= f_hi) {
    // White on the map, so named by a label rather than in the (white) legend.
    Series line;
    line.x = {t0, t1};
    line.y = {f, f};
    line.dashed = true;
    line.line_width = 1.5;
    line.rgb = "#ffffff";
    p.series.push_back(std::move(line));
    const bool shudder = det && det->verdict != analysis::Verdict::kNone;
    p.labels.push_back({t0, f, (shudder ? "dominant " : "strongest peak ") + plot_number("%.1f", f) + " Hz"});
  }
  if (det && det->verdict != analysis::Verdict::kNone && std::isfinite(det->onset_time_s)) {
    Series onset;
    onset.label = "onset " + plot_number("%.3g", det->onset_time_s) + " s (" + verdict_text(det->verdict) + ")";
    onset.x = {det->onset_time_s, det->onset_time_s};
    onset.y = {p.map.y.front(), p.map.y.back()};
    onset.dashed = true;
    onset.line_width = 2.0;
    onset.rgb = "#ff7f0e";
    p.series.push_back(std::move(onset));
  }
  return p;
}

// ---- stability map -----------------------------------------------------------------------

Series contour_series(const std::vector<double>& x, const std::vector<double>& y, const Eigen::MatrixXd& v,
                      double level, const std::string& label) {
  if (v.rows() != static_cast<long>(x.size()) || v.cols() != static_cast<long>(y.size()))
    throw std::invalid_argument("contour: values must be (n_x x n_y)");
  Series s;
  s.label = label;
  const auto segment = [&s](double x0, double y0, double x1, double y1) {
    s.x.insert(s.x.end(), {x0, x1, kNaN});
    s.y.insert(s.y.end(), {y0, y1, kNaN});
  };
  for (long i = 0; i + 1 < v.rows(); ++i)
    for (long j = 0; j + 1 < v.cols(); ++j) {
      // Corners counter-clockwise: (i,j), (i+1,j), (i+1,j+1), (i,j+1); edge e joins e and e+1.
      const double c[4] = {v(i, j) - level, v(i + 1, j) - level, v(i + 1, j + 1) - level, v(i, j + 1) - level};
      if (!(std::isfinite(c[0]) && std::isfinite(c[1]) && std::isfinite(c[2]) && std::isfinite(c[3]))) continue;
      const auto ui = static_cast<std::size_t>(i), uj = static_cast<std::size_t>(j);
      const double px[4] = {x[ui], x[ui + 1], x[ui + 1], x[ui]};
      const double py[4] = {y[uj], y[uj], y[uj + 1], y[uj + 1]};
      double ex[4], ey[4];
      bool cut[4];
      int count = 0;
      for (int e = 0; e < 4; ++e) {
        const int f = (e + 1) % 4;
        cut[e] = (c[e] > 0) != (c[f] > 0);
        if (!cut[e]) continue;
        const double w = c[e] / (c[e] - c[f]);
        ex[e] = px[e] + w * (px[f] - px[e]);
        ey[e] = py[e] + w * (py[f] - py[e]);
        ++count;
      }
      if (count == 2) {
        int a = -1, b = -1;
        for (int e = 0; e < 4; ++e)
          if (cut[e]) (a < 0 ? a : b) = e;
        segment(ex[a], ey[a], ex[b], ey[b]);
      } else if (count == 4) {
        // Saddle: if the cell's mean sides with corners 0 and 2, they connect through the
        // middle and the contour cuts off corners 1 and 3; otherwise corners 0 and 2.
        const double centre = 0.25 * (c[0] + c[1] + c[2] + c[3]);
        if ((centre > 0) == (c[0] > 0)) {
          segment(ex[0], ey[0], ex[1], ey[1]);
          segment(ex[2], ey[2], ex[3], ey[3]);
        } else {
          segment(ex[3], ey[3], ex[0], ey[0]);
          segment(ex[1], ey[1], ex[2], ey[2]);
        }
      }
    }
  return s;
}

Plot stability_map_plot(const Recording& rec, const std::string& name, const std::string& source) {
  const dynamics::Map2D* m = rec.find_map("stability_map");
  if (!m)
    throw io::InputError(source, 0, "",
                         "no /analysis/stability_map: it is written for rig scenarios (shudder run on a "
                         "scenario with type = \"rig\")");
  const dynamics::Map2D::Layer* margin = m->find("margin_per_s");
  if (!margin) throw io::InputError(source, 0, "", "/analysis/stability_map has no margin_per_s layer");
  const auto axis = [](const std::string& var, const std::string& units, const char* speeds, const char* temps) {
    const std::string what = var == "speeds_rpm" ? speeds : var == "temps_C" ? temps : var;
    return what + " [" + display_units(units) + "]";
  };

  Plot p;
  const auto* force = m->find_scalar("normal_force_N");
  p.title = name + ": stability of steady sliding" +
            (force ? " at " + plot_number("%.4g", force->value / 1e3) + " kN" : std::string());
  p.xlabel = axis(m->x_name, m->x_units, "slip speed", "interface temperature");
  p.ylabel = axis(m->y_name, m->y_units, "slip speed", "interface temperature");
  p.map.x = m->x;
  p.map.y = m->y;
  p.map.values.resize(m->x.size() * m->y.size());
  for (std::size_t i = 0; i < m->x.size(); ++i)
    for (std::size_t j = 0; j < m->y.size(); ++j)
      p.map.values[i * m->y.size() + j] = margin->values(static_cast<long>(i), static_cast<long>(j));
  p.caption =
      "Stability of steady sliding on the linearised rig: the margin (largest real part of its "
      "eigenvalues) over slip speed and interface temperature, blue stable, red unstable (an "
      "oscillation grows), the black line the boundary; grey where the motor cannot hold the slip. "
      "The green line is this run's own path.";
  p.map.diverging = true;
  p.map.label = "margin [" + display_units(margin->units) + "] (> 0: grows; grey: no steady sliding)";

  Series zero = contour_series(m->x, m->y, margin->values, 0.0, "margin = 0: stable | unstable boundary");
  zero.rgb = "#000000";
  zero.line_width = 2.5;
  if (!zero.x.empty()) {
    p.series.push_back(std::move(zero));
  } else {
    const double largest = margin->values.array().isNaN().select(-INFINITY, margin->values).maxCoeff();
    p.title += largest > 0 ? ": unstable everywhere on the map" : ": stable everywhere on the map";
  }

  // The run's own path: slip vs mean interface temperature (thinned to <= 2000 points).
  const Signal* slip = rec.find("slip_rpm");
  if (!slip) slip = rec.find("speed_rpm");
  const Signal* temp = rec.find("interface_mean_temp_C");
  if (slip && temp && m->x_name == "speeds_rpm" && m->y_name == "temps_C") {
    Series path;
    path.label = "this run: " + slip->name + " vs interface_mean_temp_C";
    const std::size_t stride = std::max<std::size_t>(1, slip->values.size() / 2000);
    for (std::size_t k = 0; k < slip->values.size(); k += stride) {
      path.x.push_back(std::abs(slip->values[k]));
      path.y.push_back(temp->values[k]);
    }
    path.rgb = "#2ca02c";
    path.line_width = 2.0;
    p.series.push_back(std::move(path));
  }
  return p;
}

// ---- sweep -------------------------------------------------------------------------------

MultiPlot sweep_plot(const io::SweepTable& table, const std::string& name, const std::string& source) {
  static const std::vector<std::string> kResults = {"predicted_stable",       "predicted_margin_per_s",
                                                    "predicted_frequency_Hz", "simulated_frequency_Hz",
                                                    "amplitude_Nm",           "onset_time_s"};
  // Swept keys: the numeric columns before the results.
  std::vector<const io::SweepColumn*> keys;
  for (const auto& c : table.columns) {
    if (std::find(kResults.begin(), kResults.end(), c.name) != kResults.end()) break;
    keys.push_back(&c);
  }
  if (keys.empty()) throw io::InputError(source, 0, "", "/cases has no swept-key column before the results");
  const io::SweepColumn& key = *keys.front();
  const std::size_t n = key.values.size();
  if (n == 0) throw io::InputError(source, 0, "", "/cases is empty: the sweep has no cases");
  const auto column = [&](const std::string& c) -> std::vector<double> {
    const io::SweepColumn* col = table.find(c);
    if (!col) return std::vector<double>(n, kNaN);
    if (col->values.size() != n)
      throw io::InputError(source, 0, "",
                           "/cases/" + c + " has " + std::to_string(col->values.size()) + " rows, " + key.name +
                               " has " + std::to_string(n));
    return col->values;
  };

  // Cases in order of the key (a cartesian product repeats key values: points only then).
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return key.values[a] < key.values[b]; });
  const bool lines = keys.size() == 1;
  const auto sorted = [&](const std::vector<double>& v) {
    std::vector<double> out;
    for (std::size_t k : order) out.push_back(v[k]);
    return out;
  };
  const std::vector<double> x = sorted(key.values);
  const auto make = [&](const std::string& label, const std::vector<double>& y, int color, int pt) {
    Series s;
    s.label = label;
    s.x = x;
    s.y = sorted(y);
    s.color = color;
    s.point_type = pt;
    s.style = lines ? SeriesStyle::kLinesPoints : SeriesStyle::kPoints;
    s.point_size = 1.0;
    return s;
  };

  // Two panels on one x axis, each with its own zero: a frequency and a growth rate are
  // different quantities, and one axis each on the same panel invited reading one off the other.
  const std::string title = name + ": sweep of " + key.name + " (" + std::to_string(n) + " cases" +
                            (keys.size() > 1 ? ", other swept keys pooled" : std::string()) + ")";
  const std::string xlabel = key.name + (key.units.empty() ? std::string() : " [" + display_units(key.units) + "]");
  // Markers on the first and last case stay clear of the borders.
  const double pad = x.back() > x.front() ? 0.04 * (x.back() - x.front()) : 0.5 * std::max(1.0, std::abs(x.front()));
  Plot top;
  top.title = "frequency: predicted (linearised) and simulated (detector)";
  top.xlabel = xlabel;
  top.ylabel = "frequency [Hz]";
  top.x_min = x.front() - pad;
  top.x_max = x.back() + pad;
  Series predicted = make("predicted frequency (linearised)", column("predicted_frequency_Hz"), 0, 7);
  Series simulated = make("simulated frequency (detector)", column("simulated_frequency_Hz"), 1, 2);
  simulated.style = SeriesStyle::kPoints;
  simulated.point_size = 2.0;
  simulated.rgb = "#000000";
  for (auto* s : {&predicted, &simulated})
    if (has_finite(*s)) top.series.push_back(std::move(*s));
  if (top.series.empty()) {
    // Nothing oscillates anywhere (e.g. a prescribed-slip sweep): show the amplitude instead.
    top.title = "simulated amplitude (no case oscillates)";
    top.ylabel = "amplitude [N m]";
    top.series.push_back(make("simulated amplitude", column("amplitude_Nm"), 1, 7));
  }

  // Below: the predicted margin, with the simulated verdict as the marker on each case.
  Plot bottom;
  bottom.title = "predicted margin (> 0: unstable), marked with each case's simulated verdict";
  bottom.xlabel = xlabel;
  bottom.ylabel = "predicted margin [1/s]";
  bottom.x_min = top.x_min;
  bottom.x_max = top.x_max;
  const std::vector<double> margin = column("predicted_margin_per_s");
  Series m = make("predicted margin", margin, 5, 1);
  m.style = lines ? SeriesStyle::kLines : SeriesStyle::kPoints;  // pooled cases: no zigzag
  m.dashed = true;
  m.line_width = 1.5;
  m.point_size = 2.5;
  if (has_finite(m)) {
    bottom.series.push_back(std::move(m));
    Series zero;
    zero.label = "margin = 0";
    zero.x = {bottom.x_min, bottom.x_max};
    zero.y = {0.0, 0.0};
    zero.rgb = "#7f7f7f";
    zero.line_width = 1.0;
    bottom.series.push_back(std::move(zero));
    struct Marker {
      analysis::Verdict verdict;
      const char* label;
      int pt;
      const char* rgb;
    };
    static constexpr Marker kMarkers[] = {{analysis::Verdict::kNone, "simulated: no shudder", 6, "#2ca02c"},
                                          {analysis::Verdict::kVibration, "simulated: vibration", 7, "#d62728"},
                                          {analysis::Verdict::kStickSlip, "simulated: stick-slip", 9, "#9467bd"}};
    for (const auto& mk : kMarkers) {
      Series s;
      s.label = mk.label;
      for (std::size_t k : order)
        if (k < table.text_column.size() && table.text_column[k] == analysis::to_string(mk.verdict) &&
            std::isfinite(margin[k])) {
          s.x.push_back(key.values[k]);
          s.y.push_back(margin[k]);
        }
      if (s.x.empty()) continue;
      s.style = SeriesStyle::kPoints;
      s.point_type = mk.pt;
      s.point_size = 1.8;
      s.rgb = mk.rgb;
      bottom.series.push_back(std::move(s));
    }
  }

  MultiPlot figure;
  figure.title = title;
  figure.caption = "Against " + key.name +
                   ": above, the predicted frequency (line) and the simulated one (crosses); below, the "
                   "predicted margin (dashed, > 0: unstable) with each case's simulated verdict as its marker, "
                   "so prediction and simulation can be compared case by case.";
  figure.rows.push_back({std::move(top)});
  if (!bottom.series.empty()) figure.rows.push_back({std::move(bottom)});
  figure.height_px = figure.rows.size() > 1 ? 900 : 600;
  return figure;
}

// ---- files -------------------------------------------------------------------------------

MultiPlot run_plot(PlotKind kind, const Recording& rec, const std::string& name, const std::string& source) {
  switch (kind) {
    case PlotKind::kTorque: return torque_plot(rec, name, source);
    case PlotKind::kTemperature: return temperature_plot(rec, name, source);
    case PlotKind::kSpectrum: return single_panel(spectrum_plot(rec, name, source));
    case PlotKind::kSpectrogram: return single_panel(spectrogram_plot(rec, name, source));
    case PlotKind::kStabilityMap: return single_panel(stability_map_plot(rec, name, source));
    case PlotKind::kCoupling: return coupling_plot(rec, name, source);
    case PlotKind::kSweep: break;
  }
  throw std::invalid_argument("run_plot: a sweep plot is built from a sweep table");
}

void plot_file(const std::string& h5_path, PlotKind kind, const std::string& out_path) {
  const std::string fallback = fs::path(h5_path).stem().string();
  const std::string file = fs::path(h5_path).filename().string();
  if (kind == PlotKind::kSweep) {
    io::SweepTable table;
    try {
      table = io::read_sweep_table(h5_path);
    } catch (const io::InputError&) {
      // A readable run file gets a pointed message; anything else keeps the reader's own.
      bool run = false;
      try {
        (void)io::read_run_hdf5(h5_path);
        run = true;
      } catch (const io::InputError&) {
        run = false;
      }
      if (!run) throw;
      throw io::InputError(h5_path, 0, "",
                           "no /cases table: a run file; --what sweep needs a file written by `shudder sweep`");
    }
    const std::string name = scenario_name(io::read_run_attribute(h5_path, "scenario"), fallback);
    write_multiplot(out_path, sweep_plot(table, name, h5_path));
    return;
  }
  Recording rec;
  try {
    rec = io::read_run_hdf5(h5_path);
  } catch (const io::InputError&) {
    bool sweep = false;
    try {
      (void)io::read_sweep_table(h5_path);
      sweep = true;
    } catch (const io::InputError&) {
      sweep = false;
    }
    if (!sweep) throw;
    throw io::InputError(h5_path, 0, "", "no /signals: a sweep file; use --what sweep, or plot one case's run file");
  }
  const std::string name = scenario_name(io::read_run_attribute(h5_path, "scenario"), fallback);
  write_multiplot(out_path, run_plot(kind, rec, name, h5_path));
}

}  // namespace shudder::report
