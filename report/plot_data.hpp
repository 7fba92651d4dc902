#pragma once
// What the plot builders (report/plots, report/time_plots) share: finding a recording's
// channels with an error that names the plot, the shudder detector's result on the recording,
// and the texts for numbers, units and verdicts in titles and labels.

#include <optional>
#include <string>
#include <string_view>

#include "analysis/shudder_detection.hpp"
#include "dynamics/recording.hpp"
#include "report/gnuplot.hpp"

namespace shudder::report {

/// The signal `name`; io::InputError naming `source` and `plot` if it is missing or empty.
const dynamics::Signal& require_signal(const dynamics::Recording& rec, std::string_view name, const std::string& source,
                                       const std::string& plot);

/// Uniform sample rate of time_s; io::InputError for fewer than `min_samples` samples.
double sample_rate_Hz(const dynamics::Signal& time, std::size_t min_samples, const std::string& source,
                      const std::string& plot);

/// The curve y(x) with a legend entry.
Series series_of(const dynamics::Signal& x, const dynamics::Signal& y, std::string label);

/// Whether any point of `s` is finite.
bool has_finite(const Series& s);

/// The shudder detector on a recording, with the channels and band its run was judged on
/// (studies/recording_detection.hpp; a network run's judged clutch as
/// studies/clutch_judgement.hpp judges it); nothing if the record cannot be analysed.
std::optional<analysis::ShudderResult> detect(const dynamics::Recording& rec);

/// Whether `d` found shudder (vibration or stick-slip) with a usable frequency.
bool oscillating(const std::optional<analysis::ShudderResult>& d);

/// The frequency a spectral plot centres on: the detected shudder frequency, else the
/// strongest peak the detector examined; NaN if neither.
double focus_frequency_Hz(const std::optional<analysis::ShudderResult>& d);

/// "friction-induced vibration", "stick-slip" or "no shudder".
std::string verdict_text(analysis::Verdict v);

/// `a` formatted by a printf conversion, e.g. plot_number("%.3g", 0.25).
std::string plot_number(const char* fmt, double a);

/// A duration readable at a glance: "16.9 ms" under a second, "1.02 s" from a second on.
std::string duration_text(double seconds);

/// "°C" for the files' "degC", other units as they are.
std::string display_units(const std::string& units);

}  // namespace shudder::report
