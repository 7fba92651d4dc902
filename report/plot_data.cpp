// Channels, detection and label texts shared by the plot builders; see plot_data.hpp.
#include "report/plot_data.hpp"

#include <cmath>
#include <stdexcept>

#include "studies/clutch_judgement.hpp"
#include "core/nan.hpp"
#include "io/input_error.hpp"
#include "report/text_format.hpp"
#include "studies/recording_detection.hpp"

namespace shudder::report {

const dynamics::Signal& require_signal(const dynamics::Recording& rec, std::string_view name, const std::string& source,
                                       const std::string& plot) {
  const dynamics::Signal* s = rec.find(name);
  if (!s || s->values.empty())
    throw io::InputError(source, 0, "", "no /signals/" + std::string(name) + ": the " + plot + " plot needs it");
  return *s;
}

double sample_rate_Hz(const dynamics::Signal& time, std::size_t min_samples, const std::string& source,
                      const std::string& plot) {
  const std::size_t n = time.values.size();
  if (n < min_samples)
    throw io::InputError(source, 0, "",
                         "the record has " + std::to_string(n) + " samples; the " + plot + " plot needs at least " +
                             std::to_string(min_samples));
  const double span = time.values.back() - time.values.front();
  if (!(span > 0)) throw io::InputError(source, 0, "", "time_s does not increase");
  return static_cast<double>(n - 1) / span;
}

Series series_of(const dynamics::Signal& x, const dynamics::Signal& y, std::string label) {
  Series s;
  s.label = std::move(label);
  s.x = x.values;
  s.y = y.values;
  return s;
}

bool has_finite(const Series& s) {
  for (std::size_t i = 0; i < s.x.size(); ++i)
    if (std::isfinite(s.x[i]) && std::isfinite(s.y[i])) return true;
  return false;
}

namespace {

// A network run's judged clutch, judged as the run judged it (studies/clutch_judgement.hpp):
// its loaded window, its band from the sample rate, its repeated-oscillation rule. The generic
// detection of a recording knows none of these and can find another peak (a shuffle mode's
// neighbour) than the verdict's.
std::optional<analysis::ShudderResult> network_clutch_detection(const dynamics::Recording& rec,
                                                                const std::string& clutch) {
  const dynamics::Signal* t = rec.find("time_s");
  if (!t) return std::nullopt;
  try {
    const double fs = sample_rate_Hz(*t, 2, "the run", "spectrum");
    const auto cv = studies::judge_clutch(rec, clutch, std::string(studies::judged_torque_signal(rec)), fs);
    if (!cv.judged) return std::nullopt;
    return cv.verdict.judged;
  } catch (const std::exception&) {
    return std::nullopt;  // too short a record, or a channel the judgement needs missing: nothing to mark
  }
}

}  // namespace

std::optional<analysis::ShudderResult> detect(const dynamics::Recording& rec) {
  if (const std::string* clutch = studies::network_verdict_clutch(rec)) return network_clutch_detection(rec, *clutch);
  const auto detection = studies::recording_detection(rec);
  if (!detection) return std::nullopt;
  try {
    return studies::judge_recording(*detection);
  } catch (const std::invalid_argument&) {
    return std::nullopt;
  }
}

bool oscillating(const std::optional<analysis::ShudderResult>& d) {
  return d && d->verdict != analysis::Verdict::kNone && std::isfinite(d->frequency_Hz) && d->frequency_Hz > 0;
}

double focus_frequency_Hz(const std::optional<analysis::ShudderResult>& d) {
  if (!d) return kNaN;
  if (oscillating(d)) return d->frequency_Hz;
  if (std::isfinite(d->peak_frequency_Hz) && d->peak_frequency_Hz > 0) return d->peak_frequency_Hz;
  return kNaN;
}

std::string verdict_text(analysis::Verdict v) {
  switch (v) {
    case analysis::Verdict::kVibration: return "friction-induced vibration";
    case analysis::Verdict::kStickSlip: return "stick-slip";
    case analysis::Verdict::kNone: break;
  }
  return "no shudder";
}

std::string plot_number(const char* fmt, double a) { return number(a, fmt); }

std::string duration_text(double seconds) {
  return std::abs(seconds) < 1.0 ? number(1e3 * seconds, "%.3g") + " ms" : number(seconds, "%.3g") + " s";
}

std::string display_units(const std::string& units) { return units == "degC" ? "°C" : units; }

}  // namespace shudder::report
