#include "studies/network_run.hpp"

#include <cmath>
#include <string>

#include "components/network_run.hpp"
#include "components/friction_range_block.hpp"
#include "studies/clutch_prediction.hpp"

namespace shudder::studies {

NetworkRun run_network(const components::NetworkSpec& spec) {
  components::NetworkSimulation sim = components::simulate_network(spec);
  components::BuiltNetwork& built = sim.stepper->built();
  NetworkRun run;
  run.recording = std::move(sim.recording);
  run.energy_imbalance_J = sim.energy_imbalance_J;
  run.energy_scale_J = sim.energy_scale_J;
  dynamics::Recording& rec = run.recording;

  // Verdicts, each on its clutch's loaded window (studies/clutch_judgement.hpp).
  for (const components::BuiltClutch& bc : built.clutches)
    run.verdicts.push_back(judge_clutch(rec, bc.name(),
                                        (bc.spec->judged_on.empty() ? bc.name() : bc.spec->judged_on) + ".torque_Nm",
                                        spec.settings.sample_rate_Hz));
  for (std::size_t c = 0; c < run.verdicts.size(); ++c)
    if (run.verdicts[c].judged)
      run.verdicts[c].verdict.prediction = predict_clutch(built, c, run.verdicts[c].verdict.window, sim.snapshots);
  run.worst = worst_verdict(run.verdicts);
  add_verdict_blocks(rec, run.verdicts, run.worst,
                     built.clutches.empty() ? "the network has no clutch to judge"
                                            : (run.verdicts.empty() ? "" : run.verdicts.front().reason));
  // In each wet clutch's verdict block (and the run's, for the clutch it names) the share of the
  // run its law was used outside its data, from its friction data range block.
  for (std::size_t c = 0; c < built.clutches.size(); ++c) {
    const components::BuiltClutch& bc = built.clutches[c];
    if (!bc.wet) continue;
    const auto* range = rec.find_block(std::string(components::kFrictionRangeBlock) + "." + bc.name());
    const auto* f = range ? range->find_scalar("fraction_outside") : nullptr;
    const double outside = f ? f->value : std::nan("");
    for (auto& b : rec.blocks) {
      const bool of_this_clutch =
          b.name == "verdict." + bc.name() || (b.name == "verdict" && static_cast<int>(c) == run.worst);
      const auto* verdict = b.find_text("verdict");
      if (of_this_clutch && verdict && verdict->value != "not_judged")
        b.scalars.push_back({"outside_data_fraction", "1", outside});
    }
  }
  return run;
}

}  // namespace shudder::studies
