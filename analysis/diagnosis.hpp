#pragma once
// Discrepancy diagnosis: where a model and measured runs disagree, which switchable effect is
// missing, its fitted parameters, and how much closer the model gets (docs/formats/diagnosis_json.md
//). Model-agnostic: the caller supplies a thread-safe Simulator that replays run k
// with the baseline plus a list of added effects; this file does the statistics.
//
// Method (docs/diagnosis.md has the reasoning):
//   noise      sigma of each signal from the data alone: the median absolute second difference
//              of consecutive samples, sigma = 1.4826 * MAD(d2) / sqrt(6) (white noise gives
//              Var(d2) = 6 sigma²; a smooth signal adds ~nothing at 100 Hz–1 kHz sampling).
//   misfit     J = ½ J_torque + ½ mean of J_c over the temperature signals c, J_c = mean((r/σ)²)
//              over a sample set, r = model − measured: temp_C always, sump_temp_C and ir_temp_C
//              when every run has them (the sump shows sump heating; the IR spot separates a
//              lagging sensor from stored heat). Mechanics and heat weigh half each, so three
//              thermometers do not outvote the one torque cell. J ≈ 1 at the noise.
//   hold-out   with several runs the last run is held out; with one run, alternate tenths of
//              its duration. Candidates are fitted on the rest and scored on the hold-out.
//   fitting    Eigen's Levenberg–Marquardt on log(parameter) (positivity, scale-free steps),
//              forward-difference Jacobian, several starts per effect (the best start wins).
//   selection  greedy: each candidate is fitted together with the effects added before it
//              (so an earlier stand-in can give way) and compared with those earlier effects
//              refitted alone on the same fit set; the best-scored candidate that is interior,
//              follows the residual (signature) and gains enough (DiagnosisOptions) is added;
//              stop when none is, or when every signal is within noise_tolerance × its scale.
//   segments   the residual averaged over blocks (≈1/80 of a run); a block disagrees when its
//              mean stands above 3 standard errors and above half a noise sigma; neighbouring
//              blocks of one sign join into a segment.
//   tracks     Pearson correlation of the block-mean residual with block means of features of
//              the measured run (temperature rise and rate, sliding speed, direction of the
//              speed change, dwell at low speed, normal force, time); the strongest is named.
//
// Units: noise analysis/noise_estimate; misfit, channels and sample sets analysis/misfit;
// fitting one candidate analysis/candidate_fit; the greedy search analysis/effect_selection;
// segments and tracks analysis/residual_tracking; threads core/parallel_for.hpp. The result
// holds numbers and structs; the sentences are report/diagnosis_narrative's.

#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace shudder::analysis {

/// One measured run as the diagnosis sees it (all columns the same length, time increasing).
struct DiagnosisRun {
  std::string name;  // e.g. the file name
  std::vector<double> time_s, speed_rpm, normal_force_N, torque_Nm, temp_C;
  std::vector<double> sump_temp_C, ir_temp_C;  // optional (empty); compared when every run has them
};

/// A switchable effect the diagnosis may add, with the parameters it fits (all > 0, fitted in
/// log space inside [lower, upper]; those marked `linear` are signed and fitted linearly). An
/// effect without parameters is just switched on.
struct EffectCandidate {
  std::string name;
  std::string description;                   // one line: what the effect does (for the reason)
  std::vector<std::string> parameter_names;  // scenario keys, e.g. "heat_capacity_J_per_K"
  std::vector<std::vector<double>> starts;   // initial guesses (each of parameter_names' size)
  std::vector<double> lower, upper;
  std::vector<bool> linear;  // empty, or per parameter (log_parameter_fit.hpp)
};

/// An effect switched on with parameter values (in parameter_names order).
struct EffectSetting {
  std::string effect;
  std::vector<double> values;
};

struct FittedEffect {
  std::string effect;
  std::vector<std::pair<std::string, double>> parameters;  // scenario key, value
};

/// A model's prediction of one run at the run's sample times.
struct Prediction {
  std::vector<double> torque_Nm, temp_C, sump_temp_C, ir_temp_C;  // the last two when asked
  std::vector<double> speed_rpm;  // the modelled drive speed (the reproduction check needs it)
};

/// Replays run `run` (index into the runs given to diagnose) with the baseline model plus
/// `added`. Must be thread-safe. Throws std::exception if the model cannot be simulated with
/// these parameters (the fit then treats them as infeasible).
using Simulator = std::function<Prediction(const std::vector<EffectSetting>& added, std::size_t run)>;

/// Replays run `run`'s inputs with the baseline model, but with `pseudo` (a run the baseline
/// model made, sensor noise added) in place of the measured signals. Its difference from the
/// pseudo-run's truth is the replay's own reproduction error (DiagnosisResult::channels).
/// Thread-safe; may be empty (no reproduction error counted).
using Reproducer = std::function<Prediction(const DiagnosisRun& pseudo, std::size_t run)>;

struct DiagnosisOptions {
  unsigned jobs = 1;             // threads (candidates are fitted in parallel)
  double noise_tolerance = 1.1;  // "within noise": every signal's RMS <= this × its error scale
  // Acceptance of a candidate (docs/diagnosis.md "Fair selection"), s = max(1, J_ref) with
  // J_ref the hold-out misfit of the earlier effects refitted alone on the same fit set:
  //   score = J_holdout + penalty_per_parameter · k · s,  gain = J_ref − score >= min_gain · s
  //   (a joint pair pays min_gain · s more; analysis/candidate_fit.hpp needed_gain),
  //   every own parameter interior (log-distance to each bound >= bound_margin of the log range),
  //   signature r >= min_signature.
  double min_gain = 0.02;               // hold-out misfit drop needed (noise variance units, × s)
  double penalty_per_parameter = 0.02;  // per fitted parameter, same units (× s)
  double bound_margin = 0.02;
  double min_signature = 0.3;
  // Two accepted single candidates whose scores differ by less than tie_tolerance · s explain
  // the data equally: neither is added and the search stops (StopReason::kTie). 1e-5: below what
  // the fits resolve (LM stops at 0.1 % in the parameters, which moves J at its minimum by
  // ~1e-6), far below the smallest real difference seen between two effects (2e-4 of J: a
  // bearing drag against a torque offset on one constant-force run, docs/diagnosis.md section 6).
  double tie_tolerance = 1e-5;
  // Backward check (docs/diagnosis.md "Backward check and its tie rule"): when an added effect
  // can be taken out at a held-out cost below the gain it would need, the remaining effect whose
  // parameters move most in the refit is its stand-in if one moves by more than this fraction
  // (log parameters: a factor 1 + stand_in_shift; signed ones: that fraction of their value, at
  // least bound_margin of their range). 0.2 is the accuracy the tests ask of an identified
  // parameter: a smaller move is the refit's own scatter, not a change of role.
  double stand_in_shift = 0.2;
  // At most this many effects added; the default is no limit (`shudder diagnose` passes the
  // registry's effect count, rig_models/effect_registry.hpp, which is also no limit).
  int max_effects = std::numeric_limits<int>::max();
  int max_samples_per_run = 1500;     // residuals use every k-th sample beyond this
  int max_evaluations = 60;           // LM model evaluations per fit (each = all fit runs)
  double min_noise_torque_Nm = 1e-3;  // floors for the noise estimate (noise-free data)
  double min_noise_temp_C = 1e-3;
  // Rig runs: compare torque by its mean and standard deviation over Hann-weighted blocks of
  // statistics_block_s (every half block) instead of sample by sample. A stick-slip cycle drifts
  // in phase between model and rig (1 % force moves it by a fraction of a cycle within
  // seconds), so a pointwise comparison measures phase, not physics; block statistics keep
  // level and amplitude. 1 s holds 3 stick-slip cycles at the rig's 0.5 rpm on the soft bar and
  // still follows thermal drifts of seconds; the Hann weight keeps the partial cycle out.
  // Error scale: the sensor noise over the block plus the block-to-block jitter the measured
  // statistics show beyond it, counted for model and measurement both.
  bool torque_block_statistics = false;
  double statistics_block_s = 1.0;
  // Model-form tolerance per channel (signal unit; keys torque_Nm, temp_C, sump_temp_C,
  // ir_temp_C, temp_minus_ir_C), added in quadrature to every error scale of that channel (a
  // temperature tolerance also adds the temp_minus_ir_C channel: misfit.hpp): data from another
  // simulator or a real rig differ from any model by more than their noise even when nothing
  // is missing (docs/diagnosis.md "Choosing a tolerance"). Default none.
  std::vector<std::pair<std::string, double>> tolerance;
  // Named only when found (analysis/explanation_check.hpp): the effects the search added are
  // reported as missing only if every one has its parameters interior on all runs (bound_margin)
  // and, with them, every channel is within found_gap_factor × its error scale. Without a
  // tolerance a model-form gap cannot be told from a missing effect, so any gap left above the
  // verdict's noise_tolerance leaves them not named. 2: a gap twice its scale is a misfit J four
  // times the noise, more than any single effect in the registry closes on data it is missing
  // from (docs/diagnosis.md "Named only when found").
  double found_gap_factor = 2.0;
};

/// How well one measured signal is explained. Pointwise channels: rms of model − measured
/// over samples; block-statistics channels: rms over blocks of the differences of block mean
/// and block standard deviation (the measured one with the noise removed in quadrature).
/// misfit: the channel's share of J, ≈ 1 when explained to the noise.
struct ChannelFit {
  std::string signal;      // torque_Nm, temp_C, sump_temp_C, ir_temp_C
  std::string comparison;  // "pointwise" or "block_statistics"
  double noise = 0.0;      // estimated sigma of one sample, signal unit
  double baseline_rms = 0.0, final_rms = 0.0;
  double baseline_misfit = 0.0, final_misfit = 0.0;
  // The error scale: RMS over all comparisons of sensor noise (+ jitter), reproduction error
  // and tolerance in quadrature (signal unit); the last two on their own.
  double error_scale = 0.0, reproduction = 0.0, tolerance = 0.0;
  bool within = false;  // final_misfit <= noise_tolerance²: the gap left is within the scale
};

/// explained: every channel within its error scale (with the named effects, if any);
/// partly explained: effects named, a gap remains; not explained: a gap no candidate closes.
enum class DiagnosisVerdict { kExplained, kPartlyExplained, kNotExplained };

/// RMS of model − measured over all samples of all runs (torque: block RMS when compared by
/// block statistics, see ChannelFit).
struct Misfit {
  double torque_rms_Nm = 0.0;
  double temp_rms_C = 0.0;
};

/// A stretch of one run where one signal's residual stands above the noise.
struct Disagreement {
  std::string run;
  std::string signal;  // "torque_Nm" or "temp_C"
  double t_start_s = 0.0, t_end_s = 0.0;
  double mean_error = 0.0;   // model − measured, the signal's unit
  std::string tracks;        // feature the run's residual follows most closely
  double correlation = 0.0;  // Pearson r of block-mean residual and that feature
};

/// A feature correlation of one run's residual (all features, for the report).
struct Tracking {
  std::string run, signal;
  std::vector<std::pair<std::string, double>> correlations;  // feature -> r, strongest first
};

struct CandidateScore {
  std::string effect;
  std::vector<std::pair<std::string, double>> parameters;  // fitted on the fit set
  double fit_misfit = 0.0;                                 // J on the fit set
  double holdout_misfit = 0.0;                             // J on the hold-out
  double score = 0.0;                  // holdout_misfit + penalty × parameters (+ min_gain × extra members)
  double gain = 0.0;                   // current hold-out J − score
  double signature_correlation = 0.0;  // r(current residual, change this effect makes)
  // Simulations of every fit run the fit made (the solver's start replay and, for a joint
  // candidate, its screen not counted); the runs not yet simulated at the fitted values (the
  // hold-out; all for a switch with nothing to fit: 0 evaluations) are then simulated once.
  int evaluations = 0;
  std::string failure;  // non-empty if every simulation failed
  // Why the candidate may not be added although fitted (empty: it may): a parameter at its
  // bound, a signature that does not follow the residual, or a gain below the needed one.
  std::string rejection;
  // A joint candidate (analysis/joint_step.hpp): the effects switched on together with
  // `effect`, in order; empty for a single effect. `parameters` then holds every member's.
  std::vector<std::string> joint_with;
};

struct DiagnosisStep {
  std::string effect;
  std::string description;                                 // the candidate's one-line description
  std::vector<std::pair<std::string, double>> parameters;  // refitted on all runs
  Misfit misfit;                                           // all runs, after adding the effect (all-runs parameters)
  Misfit holdout;                                          // hold-out samples, fit-set parameters
  double holdout_misfit_before = 0.0, holdout_misfit_after = 0.0;  // J
  std::vector<CandidateScore> candidates;                          // every candidate tried in this round, best first
  // Features the torque and temp_C residuals followed before this effect (pooled over the
  // runs, strongest first): the evidence the report's "why" sentence names.
  std::vector<std::pair<std::string, double>> torque_tracking_before, temp_tracking_before;
  std::vector<std::string> joint_with;  // added in the same joint step, after `effect`
};

/// The backward check's finding on one added effect that the others can do without: the
/// held-out misfit J rises by less than the gain the effect would need to be added now. Either
/// it was withdrawn, or it was kept by the tie rule (its stand-in has more parameters or came
/// later, or sits at a bound): the data cannot separate the two.
struct BackwardFinding {
  std::string effect;
  std::vector<std::pair<std::string, double>> parameters;  // its values on all runs before the check
  double holdout_cost = 0.0;  // hold-out J without it (the others refitted on the fit set) − J with it
  double needed_gain = 0.0;   // (min_gain + penalty · its parameters) · s
  bool withdrawn = false;
  std::string stand_in;                 // the effect that took over its share ("" if none moved)
  std::string stand_in_move;            // e.g. "heat_capacity_J_per_K 306.9 -> 2510" ("" if none)
  std::string kept_because;             // withdrawn == false: the tie rule's reason
  std::vector<std::string> joint_with;  // a joint step's other members: tried and withdrawn together
};

/// Why the greedy search stopped (report/diagnosis_narrative.hpp puts it in words).
struct StopReason {
  enum class Kind { kWithinNoise, kEffectLimit, kAllAdded, kNoGain, kNoFit, kTie };
  Kind kind = Kind::kAllAdded;
  double noise_tolerance = 0.0;  // kWithinNoise: the tolerance, and per channel rms / noise
  std::vector<std::pair<std::string, double>> rms_over_noise;
  int max_effects = 0;       // kEffectLimit
  double needed_gain = 0.0;  // kNoGain: the gain the best candidate needed, its name, its gain
  std::string best_effect;
  double best_gain = 0.0;
  std::string best_rejection;  // kNoGain: why the best-scored candidate was not added
  std::string tied_with;       // kTie: best_effect and this one scored the same (best_gain: its gain)
};

/// An effect the search added but the diagnosis does not name as found, and why: a parameter
/// the data pull to (within bound_margin of) its bound, or a gap left well above the error scale.
struct UnexplainedEffect {
  std::string effect;
  std::vector<std::pair<std::string, double>> parameters;  // refitted on all runs
  std::string parameter;                                   // the parameter at its bound; "" when the reason is the gap
  double bound = 0.0;                                      // the bound it sits at
  std::string reason;        // one clause: "the data pull gain to its bound 0.5" / "… leaves …"
  std::string likely_cause;  // "" when none is known
};

/// Measured and modelled signals of one run, for plots (at the residual samples).
struct RunTraces {
  std::string run;
  std::vector<double> time_s;
  std::vector<double> torque_measured, torque_baseline, torque_final;
  std::vector<double> temp_measured, temp_baseline, temp_final;
};

/// Which samples were held out to score the candidates (report/diagnosis_narrative.hpp puts it in
/// words).
struct HoldoutSplit {
  enum class Kind { kNone, kLastRun, kOddTenths };
  Kind kind = Kind::kNone;
  std::string run;  // kLastRun: the held-out run's name
};

struct DiagnosisResult {
  DiagnosisVerdict verdict = DiagnosisVerdict::kExplained;
  std::vector<std::string> runs;
  double noise_torque_Nm = 0.0, noise_temp_C = 0.0;  // estimated sigma
  HoldoutSplit holdout;
  Misfit baseline, final;
  std::vector<ChannelFit> channels;                                  // every compared signal (torque and temp first)
  double baseline_holdout_misfit = 0.0, final_holdout_misfit = 0.0;  // J
  std::vector<Disagreement> disagreements;                           // baseline model
  std::vector<Disagreement> final_disagreements;                     // final model
  std::vector<Tracking> tracking;                                    // baseline residual vs every feature
  std::vector<DiagnosisStep> steps;
  std::vector<std::string> missing_effects;  // added and found, most important first
  // Added by the search but not found (analysis/explanation_check.hpp): then nothing is named,
  // the final model is the baseline and the verdict is "not explained".
  std::vector<UnexplainedEffect> not_explained;
  bool tolerance_given = false;  // without one a model-form gap is not separated from an effect
  // The added effects with their parameters after the last joint refit on all runs (a step's
  // parameters are those when it was added; later effects may have moved them).
  std::vector<FittedEffect> final_effects;
  std::vector<CandidateScore> last_round;  // the round that stopped the search
  // The backward check: effects withdrawn (their steps are not in `steps`), in the order
  // withdrawn, and effects kept by its tie rule although the others could stand in for them.
  std::vector<BackwardFinding> withdrawn, indistinguishable;
  StopReason stop;
  std::vector<RunTraces> traces;
  // Cost split, CPU seconds over all threads: inside the Simulator vs. the rest (fitting,
  // residuals, statistics); and the wall time. Measured by diagnose() around the method (the
  // Simulator is wrapped to time each call on its thread).
  double simulation_thread_s = 0.0, fitting_thread_s = 0.0, wall_s = 0.0;
  long simulations = 0;
  std::vector<std::string> warnings;  // suspicious data (plausibility), for the caller to print
};

/// Throws std::invalid_argument if a run is too short to fit anything (fewer than 20 samples
/// or an empty hold-out/fit split), if columns differ in length, if no runs are given, or if a
/// run's temperature rises 6–15 × what the baseline predicts from its speeds (a speed_rpm
/// column in rad/s reads 9.55 × low; above that range only a warning).
DiagnosisResult diagnose(const std::vector<DiagnosisRun>& runs, const std::vector<EffectCandidate>& candidates,
                         const Simulator& simulate, const DiagnosisOptions& options, const Reproducer& reproduce = {});

}  // namespace shudder::analysis
