// `shudder convergence SCENARIO.toml`: is the scenario's verdict a property of the model or of
// its numerical steps? Runs the scenario as written and again with every numerical step it
// exposes divided by a factor (default 4) — the thermal step (`[solver] thermal_step_ms`) and
// the integrator's largest step (`[solver] max_step_ms`; a prescribed-slip run has none) — and
// prints, for every judged verdict (the run's; a network's every clutch), the two results and
// their change against the limits a converged result keeps:
//   verdict class unchanged;  dominant frequency within 3 %;  amplitude within 25 %.
// Why these limits: the detector's frequency resolution over a judged window of a second or more
// is well under 1 % at the driveline's 2–50 Hz, so 3 % is a real change of the oscillation; its
// amplitude (half peak-to-peak about a moving mean) moves with where the window's edges fall
// and with the sample grid, by up to ~10 % between equally good runs, so 25 % separates that from
// a different oscillation. Exit 0 converged, 3 not converged, 2 bad input, 1 failure
// (docs/convergence.md).
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>
#include <variant>
#include <vector>

#include "analysis/shudder_detection.hpp"
#include "app/commands.hpp"
#include "app/guarded.hpp"
#include "studies/network_run.hpp"
#include "core/overloaded.hpp"
#include "io/network_scenario.hpp"
#include "io/scenario.hpp"
#include "rig_models/model.hpp"
#include "studies/run_verdict.hpp"

namespace shudder::app {

namespace {

constexpr double kFrequencyLimit = 0.03;
constexpr double kAmplitudeLimit = 0.25;

struct JudgedVerdict {
  std::string subject;  // "run" or the clutch's name
  bool judged = false;
  std::string reason;  // why not judged
  analysis::ShudderResult result;
};

// The steps a scenario exposes, in seconds (NaN: the kind has none).
struct Steps {
  double thermal_s = NAN, max_step_s = NAN;
};

struct Outcome {
  Steps steps;
  std::vector<JudgedVerdict> verdicts;
};

JudgedVerdict judged_run(const dynamics::Recording& rec) {
  JudgedVerdict v{"run", true, "", {}};
  try {
    v.result = studies::judge_run(rec).judged;
  } catch (const std::invalid_argument& e) {
    v.judged = false;
    v.reason = e.what();
  }
  return v;
}

Outcome evaluate(const std::string& text, const std::string& path) {
  Outcome o;
  if (io::scenario_type_of_text(text, path) == "network") {
    const io::NetworkScenario sc = io::load_network_scenario_text(text, path);
    o.steps = {sc.spec.settings.thermal_step_s, sc.spec.settings.integrator.max_step_s};
    const studies::NetworkRun run = studies::run_network(sc.spec);
    for (const auto& c : run.verdicts) o.verdicts.push_back({c.clutch, c.judged, c.reason, c.verdict.judged});
    return o;
  }
  const io::Scenario sc = io::load_scenario_text(text, path);
  const clutch::WetClutch clutch = sc.make_clutch();
  std::visit(
      overloaded{[&](const rig_models::PrescribedSlipModel& m) { o.steps.thermal_s = m.settings.thermal_step_s; },
                 [&](const rig_models::RigModel& m) {
                   o.steps = {m.settings.thermal_step_s, m.params.integrator.max_step_s};
                 },
                 [&](const rig_models::DrivelineModel& m) {
                   o.steps = {m.settings.slow_step_s, m.params.integrator.max_step_s};
                 }},
      sc.model);
  const dynamics::Recording rec = std::visit([&](const auto& m) { return rig_models::simulate(m, clutch); }, sc.model);
  o.verdicts.push_back(judged_run(rec));
  return o;
}

std::string verdict_text(const JudgedVerdict& v) {
  return v.judged ? std::string(analysis::to_string(v.result.verdict)) : std::string("not judged");
}

std::string figure(double value, const char* unit) {
  if (!std::isfinite(value)) return "-";
  char b[64];
  std::snprintf(b, sizeof b, "%.4g %s", value, unit);
  return b;
}

// Prints one verdict's comparison; returns whether it converged.
bool compare(const JudgedVerdict& a, const JudgedVerdict& b) {
  const bool same_class = a.judged == b.judged && (!a.judged || a.result.verdict == b.result.verdict);
  const bool oscillates = same_class && a.judged && a.result.verdict != analysis::Verdict::kNone;
  const auto change = [](double x, double y) { return (y - x) / std::abs(x); };
  const double df = oscillates ? change(a.result.frequency_Hz, b.result.frequency_Hz) : NAN;
  const double da = oscillates ? change(a.result.amplitude_Nm, b.result.amplitude_Nm) : NAN;
  const bool f_ok = !oscillates || std::abs(df) <= kFrequencyLimit;
  const bool a_ok = !oscillates || std::abs(da) <= kAmplitudeLimit;
  const auto pct = [](double x) {
    char b[32];
    std::snprintf(b, sizeof b, "%+.1f %%", 100 * x);
    return std::string(b);
  };
  std::printf("  %s\n", a.subject.c_str());
  std::printf("    %-11s %-18s %-18s %-10s %s\n", "verdict", verdict_text(a).c_str(), verdict_text(b).c_str(),
              same_class ? "same" : "CHANGED", "must stay");
  if (oscillates) {
    std::printf("    %-11s %-18s %-18s %-10s %s\n", "frequency", figure(a.result.frequency_Hz, "Hz").c_str(),
                figure(b.result.frequency_Hz, "Hz").c_str(), (pct(df) + (f_ok ? "" : " !")).c_str(), "within 3 %");
    std::printf("    %-11s %-18s %-18s %-10s %s\n", "amplitude", figure(a.result.amplitude_Nm, "N m").c_str(),
                figure(b.result.amplitude_Nm, "N m").c_str(), (pct(da) + (a_ok ? "" : " !")).c_str(), "within 25 %");
  }
  if (!a.judged) std::printf("    not judged: %s\n", a.reason.c_str());
  return same_class && f_ok && a_ok;
}

std::string ms(double s) { return figure(1e3 * s, "ms"); }

}  // namespace

int convergence_command(const ConvergenceOptions& opt) {
  return guarded(opt.scenario, "convergence check", [&]() -> int {
    const std::string text = io::read_scenario_text(opt.scenario);
    const Outcome base = evaluate(text, opt.scenario);
    std::string refined = text;
    if (std::isfinite(base.steps.thermal_s))
      refined = io::set_scenario_key(refined, opt.scenario, "solver.thermal_step_ms",
                                     1e3 * base.steps.thermal_s / opt.factor);
    if (std::isfinite(base.steps.max_step_s))
      refined =
          io::set_scenario_key(refined, opt.scenario, "solver.max_step_ms", 1e3 * base.steps.max_step_s / opt.factor);
    const Outcome fine = evaluate(refined, opt.scenario);

    std::printf("Convergence of %s: every numerical step divided by %g\n", opt.scenario.c_str(), opt.factor);
    std::printf("  thermal step %s -> %s", ms(base.steps.thermal_s).c_str(), ms(fine.steps.thermal_s).c_str());
    if (std::isfinite(base.steps.max_step_s))
      std::printf("; largest integrator step %s -> %s", ms(base.steps.max_step_s).c_str(),
                  ms(fine.steps.max_step_s).c_str());
    std::printf("\n    %-11s %-18s %-18s %-10s %s\n", "", "as written", "steps divided", "change", "limit");
    bool converged = base.verdicts.size() == fine.verdicts.size();
    for (std::size_t i = 0; i < base.verdicts.size() && i < fine.verdicts.size(); ++i)
      converged = compare(base.verdicts[i], fine.verdicts[i]) && converged;
    if (converged) {
      std::printf("CONVERGED: the verdicts do not depend on the steps.\n");
      return 0;
    }
    std::printf(
        "NOT CONVERGED: a verdict depends on the step size; give the scenario smaller steps "
        "([solver] thermal_step_ms, max_step_ms) until this check passes.\n");
    return 3;
  });
}

}  // namespace shudder::app
