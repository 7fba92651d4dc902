// The Python module `shudder` (docs/python.md): load a scenario (file or TOML string) with keys
// overridden as `shudder sweep --set` sets them, run it into numpy signals with units, scalars
// and the verdict, and call sweep / screen / diagnose / characterise / compare — the CLI's own code (app/, io/). Errors
// are Python exceptions carrying the CLI's one-line messages: shudder.InputError (the CLI's
// exit 2: its line after "shudder: error: ") and shudder.NumericalError (exit 1: its line after
// "shudder: "), both subclasses of shudder.Error. The GIL is released while shudder computes.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unistd.h>
#include <utility>
#include <vector>

#include "app/commands.hpp"
#include "app/guarded.hpp"
#include "io/hdf5_sweep.hpp"
#include "io/input_error.hpp"
#include "io/network_scenario.hpp"
#include "python/py_run.hpp"

namespace py = pybind11;
namespace fs = std::filesystem;
using namespace shudder;

namespace {

// C++ types registered as the module's exception types (message = the CLI line's tail).
struct InputErrorPy : std::runtime_error {
  using std::runtime_error::runtime_error;
};
struct NumericalErrorPy : std::runtime_error {
  using std::runtime_error::runtime_error;
};

std::string tail(const std::string& line, const std::string& prefix) {
  return line.compare(0, prefix.size(), prefix) == 0 ? line.substr(prefix.size()) : line;
}

[[noreturn]] void raise(const app::Failure& f) {
  if (f.exit_code == 2) throw InputErrorPy(tail(f.line, "shudder: error: "));
  throw NumericalErrorPy(tail(f.line, "shudder: "));
}

// Runs `body` without the GIL; its exception becomes the CLI's failure, raised with the GIL.
template <class Body>
auto without_gil(const std::string& context, const char* what, Body&& body) {
  std::optional<decltype(body())> result;
  std::optional<app::Failure> failure;
  {
    py::gil_scoped_release release;
    try {
      result.emplace(body());
    } catch (const std::exception&) {
      failure = app::current_failure(context, what);
    }
  }
  if (failure) raise(*failure);
  return std::move(*result);
}

// Runs a CLI command (stdout as the CLI prints it), its error line raised instead of printed.
template <class Command>
void command(const std::string& name, Command&& cmd) {
  app::Failure failure;
  int rc = 0;
  {
    py::gil_scoped_release release;
    struct Sink {  // this thread's guarded() reports to `failure` until the command returns
      explicit Sink(app::Failure* f) { app::failure_sink = f; }
      ~Sink() { app::failure_sink = nullptr; }
    } sink(&failure);
    rc = cmd();
    std::fflush(stdout);
  }
  if (rc == 0) return;
  if (failure.line.empty()) failure = {rc, "shudder: " + name + " failed (see the message above)"};
  failure.exit_code = rc;
  raise(failure);
}

// {"key": value} → the sweep's (key, number) pairs; a value that is not a number is the input
// error `sweep --set` gives for a non-numeric value.
std::vector<std::pair<std::string, double>> overrides_of(const py::object& obj, const std::string& path) {
  std::vector<std::pair<std::string, double>> out;
  if (obj.is_none()) return out;
  for (const auto& [k, v] : obj.cast<py::dict>()) {
    const auto key = py::str(k).cast<std::string>();
    if (!py::isinstance<py::float_>(v) && !py::isinstance<py::int_>(v))
      throw InputErrorPy(io::InputError(path, 0, key,
                                        "override " + py::repr(v).cast<std::string>() +
                                            " is not a number; only numeric keys can be set "
                                            "(as with sweep --set)")
                             .what());
    out.emplace_back(key, v.cast<double>());
  }
  return out;
}

py::array_t<double> array(const std::vector<double>& v) {
  return py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data());
}

py::array_t<double> array(const Eigen::MatrixXd& m) {
  py::array_t<double> a({m.rows(), m.cols()});
  auto w = a.mutable_unchecked<2>();
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (Eigen::Index j = 0; j < m.cols(); ++j) w(i, j) = m(i, j);
  return a;
}

// A scenario as loaded (and checked); its text is what a run stores.
struct Scenario {
  io::Scenario sc;
};

Scenario load(const py::object& path, const py::object& toml, const std::string& source, const py::object& overrides) {
  if (path.is_none() == toml.is_none())
    throw InputErrorPy("shudder.load: give a scenario file or toml= (TOML text), not both or neither");
  const std::string p = path.is_none() ? source : py::str(path).cast<std::string>();
  const std::string text = toml.is_none() ? "" : toml.cast<std::string>();
  if (!toml.is_none() && text.empty()) throw InputErrorPy(p + ": the TOML text is empty; give a scenario");
  const auto ov = overrides_of(overrides, p);
  const bool text_without_source = !toml.is_none() && source == "<string>";
  return {without_gil(p, "simulation", [&] {
    try {
      return python::load_with_overrides(text, p, ov);
    } catch (const io::InputError& e) {
      // TOML text without source=: say how to read its relative fluid path from the scenario's folder.
      const std::string what = e.what();
      if (!text_without_source || what.find("key 'clutch.fluid'") == std::string::npos) throw;
      throw io::InputError(io::InputError::Verbatim{},
                           what + "; give source='path/to/the_scenario.toml' to read it from that file's folder");
    }
  })};
}

// A run's results as Python values.
struct Result {
  std::string name;
  std::string scenario_text;
  py::dict signals, units, scalars, scalar_units, blocks, maps;
  py::object verdict = py::none();
  py::list warnings;
  py::object grid_r_m = py::none(), grid_z_m = py::none();
  py::list snapshots;  // [(time_s, temp_C (n_z x n_r))]
  double wall_time_s = 0.0;
};

Result to_python(const std::string& name, const std::string& text, const python::RunOutcome& o) {
  Result r;
  r.name = name;
  r.scenario_text = text;
  r.wall_time_s = o.wall_time_s;
  const auto& rec = o.recording;
  for (const auto& s : rec.signals) {
    r.signals[py::str(s.name)] = array(s.values);
    r.units[py::str(s.name)] = s.units;
  }
  for (const auto& s : rec.scalars) {
    r.scalars[py::str(s.name)] = s.value;
    r.scalar_units[py::str(s.name)] = s.units;
  }
  for (const auto& b : rec.blocks) {
    py::dict d, units;
    d["description"] = b.description;
    for (const auto& t : b.texts) d[py::str(t.name)] = t.value;
    for (const auto& s : b.scalars) {
      d[py::str(s.name)] = s.value;
      units[py::str(s.name)] = s.units;
    }
    d["units"] = units;
    r.blocks[py::str(b.name)] = d;
  }
  if (r.blocks.contains("verdict")) r.verdict = r.blocks["verdict"];
  for (const auto& m : rec.maps) {
    py::dict d, layers, units;
    d["description"] = m.description;
    d["x_name"] = m.x_name;
    d["x_units"] = m.x_units;
    d["x"] = array(m.x);
    d["y_name"] = m.y_name;
    d["y_units"] = m.y_units;
    d["y"] = array(m.y);
    for (const auto& l : m.layers) {
      layers[py::str(l.name)] = array(l.values);
      units[py::str(l.name)] = l.units;
    }
    d["layers"] = layers;
    d["units"] = units;
    r.maps[py::str(m.name)] = d;
  }
  if (!rec.grid_r_m.empty()) r.grid_r_m = array(rec.grid_r_m);
  if (!rec.grid_z_m.empty()) r.grid_z_m = array(rec.grid_z_m);
  for (const auto& s : rec.snapshots) r.snapshots.append(py::make_tuple(s.time_s, array(s.temp_C)));
  for (const auto& w : o.warnings) r.warnings.append(w);
  return r;
}

Result run(const py::object& scenario, const py::object& overrides, const py::object& output, bool force) {
  // A network scenario file (docs/formats/network_file.md) runs through its own path.
  if (!py::isinstance<Scenario>(scenario)) {
    const std::string p = py::str(scenario).cast<std::string>();
    if (without_gil(p, "simulation", [&] { return io::scenario_type(p); }) == "network") {
      const auto ov = overrides_of(overrides, p);
      const std::string out = output.is_none() ? "" : py::str(output).cast<std::string>();
      std::string name, text;
      auto outcome = without_gil(p, "simulation", [&] { return python::run_network(p, ov, out, name, text); });
      return to_python(name, text, outcome);
    }
  }
  Scenario s =
      py::isinstance<Scenario>(scenario) ? scenario.cast<Scenario>() : load(scenario, py::none(), "", py::none());
  if (!overrides.is_none()) s = load(py::none(), py::str(s.sc.text), s.sc.path, overrides);
  const std::string out = output.is_none() ? "" : py::str(output).cast<std::string>();
  auto outcome = without_gil(s.sc.path, "simulation", [&] { return python::run(s.sc, out, force); });
  return to_python(s.sc.name, s.sc.text, outcome);
}

// Numbers as the CLI's comma-separated lists ("150,250.5"), every double exact. (A stream,
// not string `+`: GCC 12 reports a false -Wrestrict on the latter at -O3.)
std::string comma_separated(const py::handle& numbers) {
  std::ostringstream os;
  os.precision(17);
  const char* sep = "";
  for (const auto& x : numbers) {
    os << sep << x.cast<double>();
    sep = ",";
  }
  return os.str();
}

// A scratch file for a command's JSON, removed after reading.
struct ScratchFile {
  std::string path;
  ScratchFile() {
    static std::atomic<unsigned> n{0};
    path =
        (fs::temp_directory_path() / ("shudder_py_" + std::to_string(getpid()) + "_" + std::to_string(n++) + ".json"))
            .string();
  }
  ~ScratchFile() {
    std::error_code ignored;
    fs::remove(path, ignored);
  }
  py::object json() const {
    std::ifstream in(path);
    const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    return py::module_::import("json").attr("loads")(text);
  }
};

py::dict sweep(const std::string& scenario, const py::object& sets, const std::string& output, unsigned jobs,
               bool keep_parts, const std::string& report, bool force) {
  app::SweepOptions o;
  o.scenario = scenario;
  o.output = output;
  o.jobs = jobs;
  o.keep_parts = keep_parts;
  o.report = report;
  o.force = force;
  o.quiet = true;
  // {"key": "START:STOP:STEP" | [v1, v2, ...]} or ["KEY=...", ...]: the CLI's --set arguments.
  if (py::isinstance<py::dict>(sets)) {
    for (const auto& [k, v] : sets.cast<py::dict>()) {
      std::string arg = py::str(k).cast<std::string>() + "=";
      if (py::isinstance<py::str>(v)) {
        arg += v.cast<std::string>();
      } else {
        arg += comma_separated(v);
      }
      o.sets.push_back(arg);
    }
  } else {
    o.sets = sets.cast<std::vector<std::string>>();
  }
  command("sweep", [&] { return app::sweep_command(o); });
  const io::SweepTable t = without_gil(output, "sweep", [&] { return io::read_sweep_table(output); });
  py::dict cases, units;
  for (const auto& c : t.columns) {
    cases[py::str(c.name)] = array(c.values);
    units[py::str(c.name)] = c.units;
  }
  cases[py::str(t.text_column_name)] = t.text_column;
  cases[py::str(io::kSweepMessageColumn)] = t.message_column;
  py::dict out;
  out["cases"] = cases;
  out["units"] = units;
  out["path"] = output;
  return out;
}

py::object screen(const std::string& fluid, const std::string& rig, double load_N, const py::object& temps) {
  app::ScreenOptions o;
  o.fluid = fluid;
  o.rig = rig;
  o.load_N = load_N;
  if (!temps.is_none()) o.temps = comma_separated(temps);
  const ScratchFile json;
  o.json = json.path;
  // Exit 3 is "NOT JUDGED" (no index computed): an answer, in the JSON's verdict_level, not an error.
  command("screening", [&] {
    const int rc = app::screen_command(o);
    return rc == 3 ? 0 : rc;
  });
  return json.json();
}

py::object diagnose(const std::string& model, const std::vector<std::string>& runs, unsigned jobs,
                    const py::object& max_effects, const std::string& report) {
  app::DiagnoseOptions o;
  o.model = model;
  o.runs = runs;
  o.jobs = jobs;
  if (!max_effects.is_none()) o.max_effects = max_effects.cast<int>();
  o.report = report;
  const ScratchFile json;
  o.json = json.path;
  command("diagnosis", [&] { return app::diagnose_command(o); });
  return json.json();
}

// A CLI option whose allowed values CLI11 checks on the command line: checked here too, so a bad
// value is the same kind of error (shudder.InputError) naming the option and what is allowed.
void require_choice(const std::string& option, const std::string& value, const std::vector<std::string>& allowed) {
  for (const auto& a : allowed)
    if (value == a) return;
  std::string list;
  for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
  throw InputErrorPy(option + ": '" + value + "' is not one of " + list);
}

py::object characterise(const std::vector<std::string>& runs, const std::string& output, double nu40_cSt,
                        double nu100_cSt, const std::string& law, const std::string& compensation,
                        const std::string& temperature_channel, const std::string& radius, int interfaces,
                        double bearing_drag_mu, const std::string& report, const std::string& name) {
  require_choice("--law", law, {"maki", "linear", "table"});
  require_choice("--compensation", compensation, {"none", "linear", "quadratic"});
  require_choice("--temperature-channel", temperature_channel, {"temp_C", "ir_temp_C"});
  require_choice("--radius", radius, {"uniform_wear", "uniform_pressure"});
  if (interfaces < 1 || interfaces > 100)
    throw InputErrorPy("--interfaces: " + std::to_string(interfaces) + " is not in [1, 100]");
  if (!(bearing_drag_mu >= 0.0 && bearing_drag_mu <= 0.1))
    throw InputErrorPy("--bearing-drag-mu: " + std::to_string(bearing_drag_mu) + " is not in [0, 0.1]");
  app::CharacteriseOptions o;
  o.runs = runs;
  o.output = output;
  o.nu40_cSt = nu40_cSt;
  o.nu100_cSt = nu100_cSt;
  o.law = law;
  o.compensation = compensation;
  o.temperature_channel = temperature_channel;
  o.radius = radius;
  o.interfaces = interfaces;
  o.bearing_drag_mu = bearing_drag_mu;
  o.report = report;
  o.name = name;
  const ScratchFile json;
  o.json = json.path;
  command("characterisation", [&] { return app::characterise_command(o); });
  return json.json();
}

py::object compare(const std::vector<std::string>& fluids, const std::vector<std::string>& rigs,
                   const py::object& temps, double load_N, double viscosity_cSt, const std::string& report) {
  app::CompareOptions o;
  o.fluids = fluids;
  o.rigs = rigs;
  if (!temps.is_none()) o.temps = comma_separated(temps);
  o.load_N = load_N;
  o.viscosity_cSt = viscosity_cSt;
  o.report = report;
  const ScratchFile json;
  o.json = json.path;
  command("comparison", [&] { return app::compare_command(o); });
  return json.json();
}

}  // namespace

PYBIND11_MODULE(shudder, m) {
  m.doc() = "shudder: stick-slip and shudder in wet-clutch drivetrains (docs/python.md)";
  m.attr("__version__") = SHUDDER_BUILD_VERSION;

  static py::exception<std::runtime_error> error(m, "Error");
  static py::exception<InputErrorPy> input_error(m, "InputError", error.ptr());
  static py::exception<NumericalErrorPy> numerical_error(m, "NumericalError", error.ptr());
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputErrorPy& e) {
      input_error(e.what());
    } catch (const NumericalErrorPy& e) {
      numerical_error(e.what());
    }
  });

  py::class_<Scenario>(m, "Scenario", "A loaded, checked scenario (shudder.load)")
      .def_property_readonly("name", [](const Scenario& s) { return s.sc.name; })
      .def_property_readonly("description", [](const Scenario& s) { return s.sc.description; })
      .def_property_readonly("path", [](const Scenario& s) { return s.sc.path; })
      .def_property_readonly(
          "text", [](const Scenario& s) { return s.sc.text; }, "The TOML text a run stores")
      .def_property_readonly("fluid_path", [](const Scenario& s) { return s.sc.fluid_path; })
      .def_property_readonly("warnings", [](const Scenario& s) { return s.sc.warnings; })
      .def("__repr__",
           [](const Scenario& s) { return "<shudder.Scenario '" + s.sc.name + "' from " + s.sc.path + ">"; });

  py::class_<Result>(m, "Result", "One run's results (shudder.run)")
      .def_readonly("name", &Result::name)
      .def_readonly("scenario_text", &Result::scenario_text)
      .def_readonly("signals", &Result::signals, "name -> numpy array (time_s first); units in .units")
      .def_readonly("units", &Result::units)
      .def_readonly("scalars", &Result::scalars, "name -> float; units in .scalar_units")
      .def_readonly("scalar_units", &Result::scalar_units)
      .def_readonly("verdict", &Result::verdict, "the shudder verdict block (dict) or None")
      .def_readonly("blocks", &Result::blocks)
      .def_readonly("maps", &Result::maps)
      .def_readonly("grid_r_m", &Result::grid_r_m)
      .def_readonly("grid_z_m", &Result::grid_z_m)
      .def_readonly("snapshots", &Result::snapshots, "[(time_s, temp_C array (n_z x n_r))]")
      .def_readonly("warnings", &Result::warnings)
      .def_readonly("wall_time_s", &Result::wall_time_s)
      .def("__repr__", [](const Result& r) {
        std::string v = r.verdict.is_none() ? "none" : py::str(r.verdict["verdict"]).cast<std::string>();
        return "<shudder.Result '" + r.name + "': " + std::to_string(r.signals.size()) + " signals, verdict " + v + ">";
      });

  m.def("load", &load, py::arg("path") = py::none(), py::kw_only(), py::arg("toml") = py::none(),
        py::arg("source") = "<string>", py::arg("overrides") = py::none(),
        "Load a scenario from a file, or from TOML text (toml=), with numeric keys overridden (the names\n"
        "`shudder sweep --set` uses). A relative `fluid = ...` path is read from the scenario file's folder;\n"
        "for toml= text from the folder of `source` (which also names the text in messages), or from the\n"
        "current directory when source= is not given. An error about an override names the override.\n\n"
        "Examples (from the repository's root; python/tests/test_docstrings.py runs them):\n\n"
        ">>> import shudder\n"
        ">>> s = shudder.load(\"scenarios/paper_g_case1_10kN.toml\", overrides={\"drive.normal_force_N\": 2e4})\n"
        ">>> s.name, s.fluid_path\n"
        "('paper_g_case1_10kN', 'scenarios/fluids/lsc_fluid_c.toml')\n"
        ">>> text = open(\"scenarios/paper_g_case1_10kN.toml\").read()\n"
        ">>> shudder.load(toml=text, source=\"scenarios/paper_g_case1_10kN.toml\").fluid_path\n"
        "'scenarios/fluids/lsc_fluid_c.toml'\n"
        ">>> shudder.load(\"scenarios/paper_g_case1_10kN.toml\", overrides={\"drive.normal_force_N\": -5})\n"
        "Traceback (most recent call last):\n"
        "...\n"
        "shudder.InputError: overrides['drive.normal_force_N'] = -5: value -5 is out of range; allowed [0, 30000]\n");
  m.def("run", &run, py::arg("scenario"), py::kw_only(), py::arg("overrides") = py::none(),
        py::arg("output") = py::none(), py::arg("force") = false,
        "Run a scenario (shudder.Scenario or a file path) as `shudder run` does; write HDF5 if output= is given.\n\n"
        "Example (from the repository's root; python/tests/test_docstrings.py runs it): Paper G Case 1 at\n"
        "10.4 kN, about 45 N m and 90 degC after 10 s in the thesis (docs/validation.md)\n\n"
        ">>> r = shudder.run(\"scenarios/paper_g_case1_10kN.toml\")\n"
        ">>> r.units[\"torque_Nm\"], r.verdict[\"verdict\"]\n"
        "('N m', 'none')\n"
        ">>> bool(44 < r.signals[\"torque_Nm\"][-1] < 50), bool(85 < r.signals[\"temp_C\"][-1] < 95)\n"
        "(True, True)\n");
  m.def("sweep", &sweep, py::arg("scenario"), py::arg("sets"), py::kw_only(), py::arg("output"), py::arg("jobs") = 0u,
        py::arg("keep_parts") = false, py::arg("report") = "", py::arg("force") = false,
        "`shudder sweep` (threads): sets = {'key': 'START:STOP:STEP' or [values]}; returns the /cases table");
  m.def("screen", &screen, py::arg("fluid"), py::kw_only(), py::arg("rig") = "", py::arg("load_N") = 20000.0,
        py::arg("temps") = py::none(), "`shudder screen`: returns its JSON (docs/screening.md) as a dict");
  m.def("diagnose", &diagnose, py::arg("model"), py::arg("runs"), py::kw_only(), py::arg("jobs") = 0u,
        py::arg("max_effects") = py::none(), py::arg("report") = "",
        "`shudder diagnose`: returns its JSON (shudder-diagnosis/1) as a dict");
  m.def("characterise", &characterise, py::arg("runs"), py::kw_only(), py::arg("output"), py::arg("nu40_cSt"),
        py::arg("nu100_cSt"), py::arg("law") = "maki", py::arg("compensation") = "quadratic",
        py::arg("temperature_channel") = "temp_C", py::arg("radius") = "uniform_wear", py::arg("interfaces") = 1,
        py::arg("bearing_drag_mu") = 0.0, py::arg("report") = "", py::arg("name") = "",
        "`shudder characterise`: writes the fluid file `output`; returns the fit (shudder-characterisation/1) "
        "as a dict (docs/characterisation.md)");
  m.def("compare", &compare, py::arg("fluids"), py::kw_only(), py::arg("rigs") = std::vector<std::string>{},
        py::arg("temps") = py::none(), py::arg("load_N") = 20000.0, py::arg("viscosity_cSt") = 10.0,
        py::arg("report") = "", "`shudder compare`: returns its JSON (shudder-compare/1) as a dict");
}
