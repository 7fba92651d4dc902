#include "rig_models/inverse_characterisation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <string>

#include "analysis/log_parameter_fit.hpp"
#include "core/parallel_for.hpp"

namespace shudder::rig_models {

namespace {

std::string g(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

struct Replayed {
  std::vector<std::vector<double>> mu, temp_C, torque_Nm;
};

// Every run replayed with `law` and `oil`; mu_sim converted like the measurement (sign of the
// measured speed, measured force, the conversion's radius and interfaces; 0 where the
// characterisation skips the sample anyway).
Replayed replay_all(const std::vector<analysis::RampRun>& runs, const std::vector<ReplayInputs>& inputs,
                    const analysis::CharacterisationSettings& s, const std::string& channel, ReplayModel model,
                    const std::shared_ptr<const clutch::FrictionLaw>& law, const clutch::OilFlowLaw& oil,
                    unsigned jobs) {
  model.fluid.friction = law;
  model.clutch.thermal.oil_flow = oil;
  const double r_m = s.conversion.effective_radius_mm() / 1000.0;
  Replayed out;
  out.mu.resize(runs.size());
  out.temp_C.resize(runs.size());
  out.torque_Nm.resize(runs.size());
  parallel_for(runs.size(), jobs, [&](std::size_t r) {
    const ReplayOutput o = replay(model, inputs[r]);
    const std::vector<double>& temp = channel == "ir_temp_C" ? o.ir_temp_C : o.temp_C;
    const auto& run = runs[r];
    std::vector<double> mu(run.time_s.size(), 0.0);
    for (std::size_t k = 0; k < mu.size(); ++k) {
      if (!std::isfinite(o.torque_Nm[k]) || !std::isfinite(temp[k]))
        throw std::runtime_error("replaying " + run.name + " with the fitted law gave a non-finite torque or temperature");
      const double f = run.normal_force_N[k];
      if (f > 0) mu[k] = std::copysign(1.0, run.speed_rpm[k]) * o.torque_Nm[k] / (s.conversion.interfaces * f * r_m);
    }
    out.mu[r] = std::move(mu);
    out.temp_C[r] = temp;
    out.torque_Nm[r] = o.torque_Nm;
  });
  return out;
}

double rms_of(const std::vector<analysis::RampRun>& runs, const std::vector<std::vector<double>>& sim,
              std::vector<double> analysis::RampRun::*measured) {
  double ss = 0.0, n = 0.0;
  for (std::size_t r = 0; r < runs.size(); ++r)
    for (std::size_t k = 0; k < sim[r].size(); ++k) {
      ss += std::pow(sim[r][k] - (runs[r].*measured)[k], 2);
      n += 1.0;
    }
  return n > 0 ? std::sqrt(ss / n) : 0.0;
}

// Largest change of the law between iterates, over the rows' (T, F) and the node speeds.
double law_change(const analysis::Characterisation& next, const clutch::FrictionLaw& previous) {
  double d = 0.0;
  for (const auto& row : next.rows)
    for (double v : next.node_speeds_mm_s)
      d = std::max(d, std::abs(next.law->mu(v, row.temp_C, row.load_N) - previous.mu(v, row.temp_C, row.load_N)));
  return d;
}

}  // namespace

InverseCharacterisation characterise_inverse(const std::vector<analysis::RampRun>& runs,
                                             const std::vector<ReplayInputs>& inputs,
                                             const analysis::CharacterisationSettings& settings,
                                             const std::string& channel, const InverseSettings& inv) {
  if (inputs.size() != runs.size()) throw std::invalid_argument("inverse characterisation: one replay input per run");
  if (channel != "temp_C" && channel != "ir_temp_C")
    throw std::invalid_argument("inverse characterisation calibrates on temp_C or ir_temp_C, not " + channel);
  InverseCharacterisation out;
  out.sensor = analysis::characterise(runs, settings);
  out.oil_flow_start = inv.model.clutch.thermal.oil_flow;
  std::shared_ptr<const clutch::FrictionLaw> law = out.sensor.law;
  clutch::OilFlowLaw oil = out.oil_flow_start;
  const auto replay_with = [&](const std::shared_ptr<const clutch::FrictionLaw>& l, const clutch::OilFlowLaw& o) {
    ++out.replays;
    return replay_all(runs, inputs, settings, channel, inv.model, l, o, inv.jobs);
  };

  analysis::CharacterisationSettings model_settings = settings;
  model_settings.compensation = analysis::Compensation::kModel;
  for (int pass = 0; pass < 2; ++pass) {
    if (inv.calibrate_oil_flow) {
      // Unknowns: e (constant fraction) and a (slip term), positive. Bounds: e from 1e-4 (no
      // cooling) to 0.2 (Paper G calls the flow through the contact "a small fraction"); a up
      // to 0.05 per (rad/s + 1): at 10 rad/s that is 0.55 of the supply, more than e's bound.
      analysis::LogParameterProblem p;
      long n = 0;
      for (const auto& r : runs) n += long(r.time_s.size());
      p.residuals = int(n);
      p.lower = {1e-4, 1e-6};
      p.upper = {0.2, 0.05};
      p.starts = {{std::clamp(oil.e, 2e-4, 0.1), std::clamp(oil.a, 1e-5, 0.01)}};
      p.max_evaluations = inv.thermal_evaluations;
      p.evaluate = [&](const std::vector<double>& v, Eigen::VectorXd& res) {
        clutch::OilFlowLaw o = oil;
        o.e = v[0];
        o.a = v[1];
        o.b = 1.0;
        Replayed rep;
        try {
          rep = replay_with(law, o);
        } catch (const std::exception&) {
          return false;  // the solver steps back from oil flows the model cannot run
        }
        res.resize(n);
        long i = 0;
        for (std::size_t r = 0; r < runs.size(); ++r)
          for (std::size_t k = 0; k < runs[r].time_s.size(); ++k) res(i++) = rep.temp_C[r][k] - runs[r].temp_C[k];
        return true;
      };
      if (pass == 0) out.temp_rms_start_C = rms_of(runs, replay_with(law, oil).temp_C, &analysis::RampRun::temp_C);
      const analysis::LogParameterFit fit = analysis::fit_log_parameters(p);
      if (!fit.feasible)
        throw std::runtime_error("the thermal calibration could not replay the runs at any oil flow tried");
      oil.e = fit.values[0];
      oil.a = fit.values[1];
      oil.b = 1.0;
    }
    bool converged = false;
    for (int it = 0; it < inv.max_iterations; ++it) {
      const Replayed rep = replay_with(law, oil);
      if (pass == 0 && it == 0) {
        out.torque_rms_sensor_Nm = rms_of(runs, rep.torque_Nm, &analysis::RampRun::torque_Nm);
        if (!inv.calibrate_oil_flow) out.temp_rms_start_C = rms_of(runs, rep.temp_C, &analysis::RampRun::temp_C);
      }
      model_settings.model_law = law;
      model_settings.model_mu = rep.mu;
      analysis::Characterisation next = analysis::characterise(runs, model_settings);
      out.last_change_mu = law_change(next, *law);
      ++out.iterations;
      law = next.law;
      out.inverse = std::move(next);
      if (out.last_change_mu < inv.tolerance_mu) {
        converged = true;
        break;
      }
    }
    if (!converged)
      throw std::runtime_error("the inverse characterisation did not converge: after " +
                               std::to_string(inv.max_iterations) + " replays the law still changes by " +
                               g(out.last_change_mu) + " in mu (tolerance " + g(inv.tolerance_mu) +
                               "); the model cannot reproduce these runs' torque — use --method sensor");
  }
  const Replayed final_rep = replay_with(law, oil);
  out.temp_rms_C = rms_of(runs, final_rep.temp_C, &analysis::RampRun::temp_C);
  out.torque_rms_Nm = rms_of(runs, final_rep.torque_Nm, &analysis::RampRun::torque_Nm);
  out.oil_flow = oil;
  return out;
}

}  // namespace shudder::rig_models
