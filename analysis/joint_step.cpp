#include "analysis/joint_step.hpp"

#include <algorithm>
#include <exception>
#include <limits>
#include <string>

#include "core/parallel_for.hpp"

namespace shudder::analysis {

std::optional<CandidateOutcome> joint_candidate(const std::vector<const EffectCandidate*>& open,
                                                const std::vector<CandidateOutcome>& singles, const Config& fold,
                                                const Predictions& fold_pred, const CandidateFitter& fitter,
                                                const MisfitModel& misfit, const DiagnosisOptions& opt) {
  std::vector<const EffectCandidate*> switches;
  for (const auto* c : open)
    if (c->parameter_names.empty()) switches.push_back(c);
  // Each pair as its start configuration: the added effects, then the two members.
  std::vector<Config> starts;
  for (std::size_t a = 0; a < switches.size(); ++a)
    for (std::size_t b = a + 1; b < switches.size(); ++b) {
      starts.push_back(fold);
      starts.back().push_back({switches[a]->name, {}});
      starts.back().push_back({switches[b]->name, {}});
    }
  const auto best_single = std::find_if(singles.begin(), singles.end(), [](const CandidateOutcome& o) { return o.ok; });
  if (best_single != singles.end() && !best_single->score.parameters.empty())
    for (const auto* s : switches) {
      starts.push_back(best_single->config);  // the added effects refitted with it, then it
      starts.back().push_back({s->name, {}});
    }
  if (starts.empty()) return std::nullopt;

  // Screen: the fit runs at each start, which alone rank the pairs (reused by the fit of the
  // chosen pair; its hold-out runs are simulated once, at its fitted values).
  const auto runs = misfit.fit().runs();
  std::vector<Predictions> screened(starts.size());
  std::vector<double> fit_misfit(starts.size(), std::numeric_limits<double>::infinity());
  parallel_for(starts.size(), opt.jobs, [&](std::size_t i) {
    try {
      screened[i] = fitter.predict(starts[i], runs, 1);
      fit_misfit[i] = misfit.misfit(misfit.fit(), screened[i]);
    } catch (const std::exception&) {
      // Not simulable at its start: not screened in.
    }
  });
  const std::size_t best =
      static_cast<std::size_t>(std::min_element(fit_misfit.begin(), fit_misfit.end()) - fit_misfit.begin());
  if (!(fit_misfit[best] < std::numeric_limits<double>::infinity())) return std::nullopt;

  CandidateOutcome pair = fitter.fit_joint(starts[best], 2, screened[best], fold_pred);
  if (!pair.ok || !pair.score.rejection.empty()) return pair;
  // A member that does as well alone explains the gap by itself: its partner is not needed.
  const std::size_t n = starts[best].size();
  for (const auto& member : {starts[best][n - 2].effect, starts[best][n - 1].effect})
    for (const auto& o : singles)
      if (o.ok && o.score.effect == member && pair.score.score >= o.score.score && pair.score.rejection.empty())
        pair.score.rejection = "no better than " + member + " alone";
  return pair;
}

}  // namespace shudder::analysis
