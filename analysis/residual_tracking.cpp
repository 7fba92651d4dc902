#include "analysis/residual_tracking.hpp"

#include "analysis/residual_analysis.hpp"

namespace shudder::analysis {

std::vector<std::pair<std::string, double>> pooled_tracking(const std::vector<DiagnosisRun>& runs, const Predictions& p,
                                                            bool torque) {
  std::vector<double> residual;
  BlockFeatures pooled;
  for (std::size_t k = 0; k < runs.size(); ++k) {
    if (!p[k]) continue;
    const auto& m = runs[k];
    const auto blocks = residual_blocks(m.time_s);
    const auto& model = torque ? p[k]->torque_Nm : p[k]->temp_C;
    const auto& meas = torque ? m.torque_Nm : m.temp_C;
    std::vector<double> r(meas.size());
    for (std::size_t i = 0; i < r.size(); ++i) r[i] = model[i] - meas[i];
    const auto rb = block_means(r, blocks);
    residual.insert(residual.end(), rb.begin(), rb.end());
    const auto f = block_features(m.time_s, m.speed_rpm, m.temp_C, m.normal_force_N, blocks);
    if (pooled.names.empty()) {
      pooled.names = f.names;
      pooled.values.assign(f.names.size(), {});
    }
    for (std::size_t j = 0; j < f.names.size(); ++j)
      pooled.values[j].insert(pooled.values[j].end(), f.values[j].begin(), f.values[j].end());
  }
  return rank_features(residual, pooled);
}

std::vector<Disagreement> disagreements(const std::vector<DiagnosisRun>& runs, const Predictions& p,
                                        double sigma_torque_Nm, double sigma_temp_C) {
  std::vector<Disagreement> out;
  for (const bool torque : {true, false}) {
    const auto ranked = pooled_tracking(runs, p, torque);
    const double sigma = torque ? sigma_torque_Nm : sigma_temp_C;
    for (std::size_t k = 0; k < runs.size(); ++k) {
      const auto& m = runs[k];
      const auto& model = torque ? p[k]->torque_Nm : p[k]->temp_C;
      const auto& meas = torque ? m.torque_Nm : m.temp_C;
      std::vector<double> r(meas.size());
      for (std::size_t i = 0; i < r.size(); ++i) r[i] = model[i] - meas[i];
      for (const auto& s : residual_segments(r, sigma, residual_blocks(m.time_s))) {
        Disagreement d;
        d.run = m.name;
        d.signal = torque ? "torque_Nm" : "temp_C";
        d.t_start_s = m.time_s[s.first_sample];
        d.t_end_s = m.time_s[s.end_sample - 1];
        d.mean_error = s.mean;
        if (!ranked.empty()) {
          d.tracks = ranked.front().first;
          d.correlation = ranked.front().second;
        }
        out.push_back(d);
      }
    }
  }
  return out;
}

std::vector<Tracking> tracking(const std::vector<DiagnosisRun>& runs, const Predictions& p) {
  std::vector<Tracking> out;
  for (const bool torque : {true, false}) {
    const std::string signal = torque ? "torque_Nm" : "temp_C";
    if (runs.size() > 1) out.push_back({"all runs", signal, pooled_tracking(runs, p, torque)});
    for (std::size_t k = 0; k < runs.size(); ++k) {
      Predictions one(runs.size());
      one[k] = p[k];
      out.push_back({runs[k].name, signal, pooled_tracking(runs, one, torque)});
    }
  }
  return out;
}

}  // namespace shudder::analysis
