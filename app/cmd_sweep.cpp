// `shudder sweep`: runs a scenario over the cartesian product of --set axes, in parallel, and
// writes one HDF5 with a /cases table (io/hdf5_sweep.hpp). Finished cases are kept in
// OUT.h5.parts/ (one run file each, tagged with the case's scenario text) so an interrupted
// sweep resumes where it stopped; the folder is removed once OUT.h5 is complete. With --mpi the
// cases run on every MPI rank instead of threads (app/mpi_sweep.hpp); the file is the same.
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iostream>
#include <mutex>
#include <new>
#include <optional>
#include <string_view>
#include <thread>
#include <variant>

#include "analysis/shudder_detection.hpp"
#include "app/commands.hpp"
#include "app/guarded.hpp"
#include "app/mpi_sweep.hpp"
#include "app/output_size.hpp"
#include "studies/network_run.hpp"
#include "core/parallel_for.hpp"
#include "dynamics/signal_names.hpp"
#include "io/hdf5_run.hpp"
#include "io/hdf5_sweep.hpp"
#include "io/input_error.hpp"
#include "io/kind_refusal.hpp"
#include "io/network_scenario.hpp"
#include "io/output_safety.hpp"
#include "report/plots.hpp"
#include "report/run_report_directory.hpp"
#include "io/scenario.hpp"
#include "io/sweep_spec.hpp"
#include "components/energy_guard.hpp"
#include "rig_models/model.hpp"
#include "studies/model_studies.hpp"

namespace shudder::app {

namespace {

namespace fs = std::filesystem;

// Signals kept per case in the sweep file (the full record stays in the part while running).
namespace sn = dynamics::signal_names;
constexpr std::string_view kKeptSignals[] = {sn::kTime, sn::kSpeed, sn::kSlip, sn::kTorque, sn::kTemp};
// A driveline case (it records the coupling) keeps its coupling's signals instead.
constexpr std::string_view kKeptCouplingSignals[] = {sn::kTime, sn::kCouplingSlip, sn::kCouplingTorque,
                                                     sn::kInterfaceMeanTemp};
// The verdict as the number the part files store (analysis::kVerdicts' order).
double verdict_code(const std::string& v) { return static_cast<double>(analysis::verdict_from_string(v)); }
// The /cases verdict of a case whose run threw (not an analysis verdict: nothing was classified).
constexpr const char* kFailed = "failed";

// A case's outcome as the part file's summary scalars.
std::vector<dynamics::Scalar> outcome_scalars(const studies::CaseOutcome& o) {
  return {{"predicted_stable", "1", o.predicted_stable ? 1.0 : 0.0},
          {"predicted_margin_per_s", "1/s", o.predicted_margin_per_s},
          {"predicted_frequency_Hz", "Hz", o.predicted_frequency_Hz},
          {"simulated_verdict_code", "1", verdict_code(o.simulated_verdict)},
          {"simulated_frequency_Hz", "Hz", o.simulated_frequency_Hz},
          {"amplitude_Nm", "N m", o.amplitude_Nm},
          {"onset_time_s", "s", o.onset_time_s}};
}

// A network case: the run's verdict (its worst clutch) and that clutch's linear prediction
// (studies/clutch_prediction.hpp) as the outcome; kept: time and every clutch's torque and slip.
studies::CaseOutcome run_network_case(const std::string& text, const std::string& path, dynamics::Recording& kept) {
  const io::NetworkScenario sc = io::load_network_scenario_text(text, path);
  const studies::NetworkRun run = studies::run_network(sc.spec);
  if (const std::string bad = components::energy_balance_violation(run.recording); !bad.empty())
    throw std::runtime_error("numerical failure: " + bad);
  kept.signals.push_back(*run.recording.find(sn::kTime));
  for (const auto& c : sc.spec.clutches)
    for (const char* q : {".torque_Nm", ".slip_rpm"}) kept.signals.push_back(*run.recording.find(c.name + q));
  studies::CaseOutcome o;
  if (run.worst >= 0) {
    const auto& v = run.verdicts[static_cast<std::size_t>(run.worst)].verdict;
    const auto& r = v.judged;
    if (v.prediction.made) {
      o.predicted_stable = !(v.prediction.margin_per_s > 0);
      o.predicted_margin_per_s = v.prediction.margin_per_s;
      o.predicted_frequency_Hz = v.prediction.frequency_Hz;
    }
    o.simulated_verdict = std::string(analysis::to_string(r.verdict));
    o.simulated_frequency_Hz = r.frequency_Hz;
    o.amplitude_Nm = r.amplitude_Nm;
    o.onset_time_s = r.onset_time_s;
  }
  return o;
}

// Runs one case and writes its part file (recording + outcome as summary scalars). A case whose
// model or run throws is a result, not a sweep failure: its part records the message (verdict
// `failed`), so the sweep finishes and a resume keeps it. Running out of memory is not a
// property of the case and stops the sweep; so does a part that cannot be written.
void run_case(const std::string& text, const std::string& path, const std::string& part) {
  dynamics::Recording kept;
  try {
    if (io::scenario_type_of_text(text, path) == "network") {
      const studies::CaseOutcome o = run_network_case(text, path, kept);
      kept.scalars = outcome_scalars(o);
      io::write_run_hdf5(part, kept, text, "", io::RunCompression::kNone);
      return;
    }
    const io::Scenario sc = io::load_scenario_text(text, path);
    const clutch::WetClutch clutch = sc.make_clutch();
    dynamics::Recording rec;
    const studies::CaseOutcome o = io::visit_kind(
        path, "scenario.type", sc.model, [&](const auto& m) { return studies::evaluate_case(m, clutch, rec); });
    // A case whose energy accounts do not close is a numerical failure, not a result.
    if (const std::string bad = components::energy_balance_violation(rec); !bad.empty())
      throw std::runtime_error("numerical failure: " + bad);
    if (rec.find(sn::kCouplingSlip)) {
      for (const std::string_view name : kKeptCouplingSignals)
        if (const auto* s = rec.find(name)) kept.signals.push_back(*s);
    } else {
      for (const std::string_view name : kKeptSignals)
        if (const auto* s = rec.find(name)) kept.signals.push_back(*s);
    }
    kept.scalars = outcome_scalars(o);
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    io::write_failed_case_part(part, text, e.what());
    return;
  }
  // A part is read back once when the sweep is assembled: not worth deflating.
  io::write_run_hdf5(part, kept, text, "", io::RunCompression::kNone);
}

// What the sweep needs of its base scenario, a network or one of the kinds.
struct SweepBase {
  bool network = false;
  std::string name, text, fluid_text;
  std::vector<std::string> fluid_paths, warnings;
};

SweepBase load_sweep_base(const std::string& path) {
  SweepBase b;
  if (io::scenario_type(path) == "network") {
    const io::NetworkScenario sc = io::load_network_scenario(path);
    if (sc.spec.clutches.empty())
      throw io::InputError(path, 0, "network", "has no clutch: a sweep judges the clutches' verdicts; add a clutch");
    b = {true, sc.name, sc.text, sc.fluid_texts, sc.fluid_paths, sc.warnings};
    return b;
  }
  const io::Scenario sc = io::load_scenario(path);
  io::visit_kind(path, "scenario.type", sc.model, [](const auto& m) { studies::require_sweep(m); });
  b = {false, sc.name, sc.text, sc.fluid_text, {sc.fluid_path}, sc.warnings};
  return b;
}

// A network case's kept data: time and two signals per clutch, 8 bytes a sample.
std::uint64_t network_case_bytes(const io::NetworkScenario& sc) {
  const double samples = std::floor(sc.spec.settings.duration_s * sc.spec.settings.sample_rate_Hz) + 1;
  return static_cast<std::uint64_t>(samples * static_cast<double>(1 + 2 * sc.spec.clutches.size()) * 8.0);
}

// The grid's rows; a grid too large to list in memory is an input error naming its size.
std::vector<std::vector<double>> list_cases(const std::vector<io::SweepAxis>& axes) {
  double n = 1.0;
  for (const auto& a : axes) n *= static_cast<double>(a.values.size());
  try {
    return io::sweep_cases(axes);
  } catch (const std::bad_alloc&) {
    char what[160];
    std::snprintf(what, sizeof what, "the grid has %.3g cases: ran out of memory listing them; reduce the --set ranges",
                  n);
    throw io::InputError("--set", 0, "", what);
  }
}

// One line naming the failed cases (at most ten indices) and the first one's message.
std::string failure_warning(const std::vector<std::size_t>& failed, std::size_t total, const std::string& first) {
  std::string ids;
  for (std::size_t i = 0; i < failed.size() && i < 10; ++i) ids += (i ? ", " : "") + std::to_string(failed[i]);
  if (failed.size() > 10) ids += ", ...";
  return "shudder: warning: " + std::to_string(failed.size()) + " of " + std::to_string(total) + " cases failed (" +
         (failed.size() > 1 ? "cases " : "case ") + ids + "); case " + std::to_string(failed.front()) + ": " + first +
         "; /cases marks them 'failed' with the message in " + io::kSweepMessageColumn + "\n";
}

void progress(std::size_t done, std::size_t total, double elapsed_s) {
  constexpr int kWidth = 30;
  const int filled = total ? static_cast<int>(kWidth * done / total) : kWidth;
  const double eta = done ? elapsed_s * static_cast<double>(total - done) / static_cast<double>(done) : 0.0;
  std::fprintf(stderr, "\r[%.*s%.*s] %zu/%zu cases, %.1f s elapsed, ~%.0f s left ", filled,
               "##############################", kWidth - filled, "..............................", done, total,
               elapsed_s, eta);
  std::fflush(stderr);
}

// The output may replace neither an input nor the report, and its directory must exist: the
// parts folder beside it is created, never the directories above it.
void check_paths(const SweepOptions& opt, const SweepBase& base) {
  std::vector<io::RolePath> outputs{{"-o", opt.output}};
  if (!opt.report.empty()) outputs.push_back({"--report", opt.report});
  std::vector<io::RolePath> inputs{{"scenario", opt.scenario}};
  for (const auto& f : base.fluid_paths) inputs.push_back({"fluid file", f});
  io::require_distinct_paths(inputs, outputs);
  for (const auto& o : outputs) io::require_output_directory(o.path);
}

// Case texts, each validated now so bad keys or values stop the sweep before it runs; the
// output's size summed over the cases (a case may change the duration or the rate).
std::vector<std::string> case_texts(const SweepOptions& opt, const SweepBase& base,
                                    const std::vector<io::SweepAxis>& axes,
                                    const std::vector<std::vector<double>>& rows) {
  std::vector<std::string> texts;
  std::uint64_t bytes = 0;
  for (const auto& row : rows) {
    std::string text = base.text;
    for (std::size_t a = 0; a < axes.size(); ++a) text = io::set_scenario_key(text, opt.scenario, axes[a].key, row[a]);
    bytes += base.network ? network_case_bytes(io::load_network_scenario_text(text, opt.scenario))
                          : estimated_sweep_bytes(io::load_scenario_text(text, opt.scenario), 1);
    texts.push_back(std::move(text));
  }
  io::require_output_size(opt.output, bytes,
                          std::to_string(texts.size()) + " cases x samples x " + std::to_string(kSweepKeptChannels) +
                              " kept signals x 8 bytes",
                          opt.force);
  return texts;
}

struct CaseParts {
  std::vector<std::string> paths;  // one run file per case, OUT.h5.parts/case_NNNNN.h5
  std::vector<std::size_t> todo;   // the cases still to run
};

// Resume: a part whose stored scenario equals the case's text is finished.
CaseParts case_parts(const fs::path& parts, const std::vector<std::string>& texts) {
  CaseParts c;
  for (std::size_t k = 0; k < texts.size(); ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "case_%05zu.h5", k);
    c.paths.push_back((parts / name).string());
    bool finished = false;
    if (std::error_code ec; fs::exists(c.paths.back(), ec)) {
      try {
        finished = io::read_run_attribute(c.paths.back(), "scenario") == texts[k];
      } catch (const io::InputError&) {
        finished = false;  // unreadable leftover: run the case again
      }
    }
    if (!finished) c.todo.push_back(k);
  }
  return c;
}

struct PoolOutcome {
  unsigned jobs = 1;
  double wall_s = 0.0;
  std::string first_error;  // the first case that threw, "" if none
  bool out_of_memory = false;
  std::string mpi_balance;  // --mpi: one summary line, the hand-out's balance
};

// The unfinished cases on a worker pool: threads here, or every MPI rank (app/mpi_sweep.hpp).
PoolOutcome run_pool(const SweepOptions& opt, mpi::Session* mpi, const std::vector<std::string>& texts,
                     const CaseParts& parts) {
  PoolOutcome r;
  const auto& todo = parts.todo;
  r.jobs = mpi ? static_cast<unsigned>(mpi->ranks())
               : std::max(1u, opt.jobs ? opt.jobs : std::thread::hardware_concurrency());
  const bool show = isatty(STDERR_FILENO) && !opt.quiet;
  std::atomic<std::size_t> done{0};
  std::mutex error_mutex;
  std::atomic<bool> out_of_memory{false};
  const auto t0 = std::chrono::steady_clock::now();
  const auto elapsed_s = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  if (mpi) {
    const auto outcome = mpi::run_cases(
        *mpi, todo, texts, parts.paths,
        [&](const std::string& text, const std::string& part) { run_case(text, opt.scenario, part); },
        show ? std::function<void(std::size_t)>([&](std::size_t n) { progress(n, todo.size(), elapsed_s()); })
             : std::function<void(std::size_t)>());
    r.first_error = outcome.first_error;
    out_of_memory = outcome.out_of_memory;
    r.mpi_balance = "Cases per MPI rank:";
    for (const std::size_t n : outcome.cases_per_rank) r.mpi_balance += " " + std::to_string(n);
    r.mpi_balance += "\n";
  } else {
    parallel_for(
        todo.size(), r.jobs,
        [&](std::size_t i) {
          const std::size_t k = todo[i];
          // What escapes run_case stops the sweep: a part that cannot be written, or memory.
          try {
            run_case(texts[k], opt.scenario, parts.paths[k]);
          } catch (const std::bad_alloc&) {
            out_of_memory = true;
          } catch (const std::exception& e) {
            const std::lock_guard lock(error_mutex);
            if (r.first_error.empty()) r.first_error = "case " + std::to_string(k) + ": " + e.what();
          }
          ++done;
        },
        show ? std::function<void()>([&] { progress(done, todo.size(), elapsed_s()); }) : std::function<void()>());
  }
  r.wall_s = elapsed_s();
  r.out_of_memory = out_of_memory;
  if (show) std::fprintf(stderr, "\n");
  return r;
}

constexpr const char* kResults[] = {"predicted_stable",       "predicted_margin_per_s", "predicted_frequency_Hz",
                                    "simulated_frequency_Hz", "amplitude_Nm",           "onset_time_s"};
constexpr const char* kResultUnits[] = {"1", "1/s", "Hz", "Hz", "N m", "s"};
constexpr std::size_t kResultCount = std::size(kResults);

// The sweep file's table from the parts: the axes' values, each case's results (NaN and its
// message for a failed case). The signals are copied by the writer one case at a time, so the
// sweep's memory does not grow with its case count.
io::SweepOutput assemble(const SweepBase& base, const std::vector<io::SweepAxis>& axes,
                         const std::vector<std::vector<double>>& rows, const std::vector<std::string>& texts,
                         const CaseParts& parts, std::vector<std::size_t>& failed) {
  io::SweepOutput out;
  out.base_scenario_text = base.text;
  out.fluid_text = base.fluid_text;
  for (const auto& a : axes) out.columns.push_back({a.key, "", {}});
  for (std::size_t r = 0; r < kResultCount; ++r) out.columns.push_back({kResults[r], kResultUnits[r], {}});
  for (std::size_t k = 0; k < texts.size(); ++k) {
    for (std::size_t a = 0; a < axes.size(); ++a) out.columns[a].values.push_back(rows[k][a]);
    out.case_scenarios.push_back(texts[k]);
    std::string message = io::read_run_attribute(parts.paths[k], io::kSweepMessageColumn);
    if (!message.empty()) {
      failed.push_back(k);
      for (std::size_t r = 0; r < kResultCount; ++r) out.columns[axes.size() + r].values.push_back(std::nan(""));
      out.text_column.emplace_back(kFailed);
      out.message_column.push_back(std::move(message));
      out.case_part_paths.emplace_back();
      continue;
    }
    const dynamics::Recording part = io::read_run_hdf5(parts.paths[k]);
    for (std::size_t r = 0; r < kResultCount; ++r)
      out.columns[axes.size() + r].values.push_back(part.find_scalar(kResults[r])->value);
    out.text_column.emplace_back(analysis::to_string(
        analysis::kVerdicts.at(static_cast<std::size_t>(part.find_scalar("simulated_verdict_code")->value))));
    out.message_column.emplace_back();
    out.case_part_paths.push_back(parts.paths[k]);
  }
  return out;
}

// Two lines: cases, jobs, time and file; the verdicts counted (and the MPI balance).
std::string sweep_summary(const SweepOptions& opt, const SweepBase& base, const io::SweepOutput& out, std::size_t axes,
                          std::size_t ran, std::size_t failed, const PoolOutcome& pool) {
  std::string summary;
  char line[512];
  std::snprintf(line, sizeof line, "Sweep of %s: %zu cases (%zu run now, %u jobs) in %.2f s -> %s\n", base.name.c_str(),
                out.case_scenarios.size(), ran, pool.jobs, pool.wall_s, opt.output.c_str());
  summary += line;
  std::size_t counts[3] = {0, 0, 0};
  for (const auto& v : out.text_column)
    if (v != kFailed) counts[static_cast<int>(verdict_code(v))]++;
  const std::string failures = failed == 0 ? "" : ", " + std::to_string(failed) + " failed";
  const auto& stable = out.columns[axes].values;  // predicted_stable
  std::snprintf(line, sizeof line, "Simulated: %zu none, %zu vibration, %zu stick-slip%s; predicted unstable: %zu\n",
                counts[0], counts[1], counts[2], failures.c_str(),
                static_cast<std::size_t>(std::count(stable.begin(), stable.end(), 0.0)));
  summary += line;
  return summary + pool.mpi_balance;
}

// --report DIR: summary.txt, sweep.png and index.html. Exit 1 when only the report failed (the
// sweep file is complete); a bad report path is the user's (InputError, exit 2).
int write_report(const SweepOptions& opt, const SweepBase& base, const io::SweepOutput& out,
                 const std::string& summary) {
  io::SweepTable table;
  table.columns = out.columns;
  table.text_column_name = out.text_column_name;
  table.text_column = out.text_column;
  table.message_column = out.message_column;
  report::Report rep;
  try {
    rep = report::write_sweep_report(opt.report, table, base.name, summary, opt.output);
  } catch (const io::InputError&) {
    throw;
  } catch (const std::exception& e) {
    std::cerr << "shudder: report failed: " << e.what() << " (the sweep itself is in " << opt.output << ")\n";
    return 1;
  }
  if (!opt.quiet) std::printf("Report: %s (%zu files)\n", opt.report.c_str(), rep.files.size());
  for (const auto& s : rep.skipped) std::cerr << "shudder: warning: report: " << s << "\n";
  return 0;
}

}  // namespace

int sweep_command(const SweepOptions& opt) {
  return guarded(opt.scenario, "sweep", [&]() -> int {
    // --mpi: every rank runs this command; rank 0 sweeps as below, the others run its cases.
    std::optional<mpi::Session> mpi_session;
    if (opt.mpi) {
      if (opt.jobs)
        throw io::InputError("--jobs", 0, "",
                             "not with --mpi: each MPI rank runs one case at a time; "
                             "choose the number of ranks with mpirun -np N");
      mpi_session.emplace();
      if (!mpi_session->coordinator()) {
        mpi::serve_cases(*mpi_session,
                         [&](const std::string& text, const std::string& part) { run_case(text, opt.scenario, part); });
        return 0;
      }
    }
    mpi::Session* const mpi = mpi_session ? &*mpi_session : nullptr;

    // The base scenario, the axes and their cases, all checked before any case runs.
    const SweepBase base = load_sweep_base(opt.scenario);
    for (const auto& w : base.warnings) std::cerr << "shudder: warning: " << w << "\n";
    if (opt.sets.empty()) throw io::InputError("--set", 0, "", "give at least one --set KEY=START:STOP:STEP");
    std::vector<io::SweepAxis> axes;
    for (const auto& s : opt.sets) axes.push_back(io::parse_sweep_axis(s));
    io::require_distinct_keys(axes);  // else cases would repeat and /cases hold two columns of one name
    const auto rows = list_cases(axes);
    check_paths(opt, base);
    const std::vector<std::string> texts = case_texts(opt, base, axes, rows);

    // Run what is not finished yet.
    const fs::path parts_dir = opt.output + ".parts";
    fs::create_directory(parts_dir);
    const CaseParts parts = case_parts(parts_dir, texts);
    if (parts.todo.size() < texts.size())
      std::cerr << "shudder: resuming: " << texts.size() - parts.todo.size() << " of " << texts.size()
                << " cases already finished in " << parts_dir.string() << "\n";
    const PoolOutcome pool = run_pool(opt, mpi, texts, parts);
    if (pool.out_of_memory)
      throw io::InputError(opt.scenario, 0, "",
                           "ran out of memory running " + std::to_string(parts.todo.size()) + " cases on " +
                               std::to_string(pool.jobs) +
                               " jobs; reduce --jobs, the duration or sample_rate_Hz "
                               "(finished cases are kept in " +
                               parts_dir.string() + ")");
    if (!pool.first_error.empty())
      throw std::runtime_error(pool.first_error + " (finished cases are kept in " + parts_dir.string() +
                               "; rerun to resume)");

    // The sweep file, then the summary and the report.
    std::vector<std::size_t> failed;
    const io::SweepOutput out = assemble(base, axes, rows, texts, parts, failed);
    io::write_sweep_hdf5(opt.output, out);
    if (!opt.keep_parts) fs::remove_all(parts_dir);
    const std::string summary = sweep_summary(opt, base, out, axes.size(), parts.todo.size(), failed.size(), pool);
    if (!failed.empty()) std::cerr << failure_warning(failed, texts.size(), out.message_column[failed.front()]);
    if (!opt.quiet) std::fputs(summary.c_str(), stdout);
    return opt.report.empty() ? 0 : write_report(opt, base, out, summary);
  });
}

}  // namespace shudder::app
