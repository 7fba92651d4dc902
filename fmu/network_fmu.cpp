// The FMI 2.0 co-simulation FMU of a user's network scenario (docs/fmu.md "Your drivetrain as
// an FMU"): one generic library, binaries/linux64/shudder_network.so, that reads the scenario
// packed by `shudder export-fmu` from its resources/ at instantiation (resources/network_fmu.toml
// names it and the export's fixed step) and runs it with components::NetworkStepper on the
// fixed-step RK4 of `shudder run --fixed-step`.
//
// GUID: the library writes the description again from the packed scenario
// (fmu/network_variables.hpp, fmu/model_description_xml.hpp) and refuses a GUID that is not its
// content GUID, so a modelDescription.xml is never paired with other resources.
//
// Time: the scenario's t = 0 is the master's start time (fmi2SetupExperiment); the network's
// own clock counts internal steps from there, so a start at 1800 s runs exactly as one at 0.
// A communication step of H is whole internal steps of h = fixed_step_s and, when H is not a
// whole multiple (to the tolerance of fmu/step_split.hpp), one shorter step at its end.
// Inputs are held over each step (zero-order hold): a changed input replaces its signal's value
// (a wet clutch's clamp force schedule with it) and restarts the stepper at the step's start,
// as a jump of a scenario's signal does. Outputs after a step: the mechanical channels at the
// step's end; the thermal channels (temperatures) at the last thermal step's end, which
// `shudder run` interpolates between thermal steps in its HDF5 file.
//
// The calling sequence, logging and get/set are fmu/fmi2_functions.cpp's.
#include <algorithm>
#include <cmath>
#include <deque>
#include <filesystem>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

#include <toml++/toml.h>

#include "components/network_channels.hpp"
#include "components/network_stepper.hpp"
#include "fmu/fmi2_instance.hpp"
#include "fmu/model_description_xml.hpp"
#include "fmu/network_variables.hpp"
#include "fmu/step_split.hpp"
#include "io/network_scenario.hpp"
#include "io/scenario.hpp"

namespace {

using namespace shudder;
namespace fs = std::filesystem;

class Instance : public fmu::InstanceBase {
 public:
  Instance(const std::string& name, const fmi2CallbackFunctions& cb, const fmu::ResourceLocation& where,
           io::NetworkScenario scenario, fmu::DescribedModel model)
      : InstanceBase(name, cb, where), sc_(std::move(scenario)), model_(std::move(model)) {}

  std::size_t variable_count() const override { return model_.variables.size(); }
  fmu::VariableInfo variable(std::size_t i) const override {
    const auto& v = model_.variables[i];
    return {v.vr, v.name, v.type, v.causality};
  }
  void set_starts() override {
    numbers.assign(model_.variables.size(), 0.0);
    texts.assign(model_.variables.size(), "");
    for (std::size_t i = 0; i < model_.variables.size(); ++i) numbers[i] = model_.variables[i].start;
  }
  void initial_outputs() override {
    if (!stepper_ || parameters_changed) build();
    apply_inputs(false);
    update_outputs();
  }
  void exit_initialisation() override {
    build();  // from the inputs as they are now: the start state (stuck contacts, speeds) depends on them
    update_outputs();
  }
  void drop_model() override { stepper_.reset(); }
  void do_step(double tc, double H) override {
    const double h = fixed_step_s();
    const fmu::StepSplit split = split_communication_step(tc, H, h);
    apply_inputs(true);
    // Whole steps end on the internal grid k·h (a product: no drift), then the shorter one.
    whole_steps_ += split.whole_steps;
    const double grid_s = whole_steps_ * h;
    if (grid_s > stepper_->simulation().time_s()) stepper_->advance_to(grid_s);
    if (split.last_fraction > 0.0) {
      stepper_->advance_to(stepper_->simulation().time_s() + split.last_fraction * h);
      // The grid restarts from the shorter step's end.
      whole_steps_ = stepper_->simulation().time_s() / h;
      log_shorter_step(H, split.whole_steps, split.last_fraction);
    }
    time_s = tc + H;
    update_outputs();
  }

 private:
  double fixed_step_s() const { return numbers[index(fmu::kFixedStepVr)]; }

  // The spec with every input's signal held from a cell, the stepper at t = 0, the outputs' channels.
  void build() {
    const double h = fixed_step_s();
    const auto& st = sc_.spec.settings;
    if (!(h > 0) || !std::isfinite(h)) throw std::invalid_argument("fixed_step_s must be a number > 0 (s)");
    const double per_thermal = st.thermal_step_s / h;
    if (std::abs(per_thermal - std::round(per_thermal)) > 1e-9 * per_thermal || std::round(per_thermal) < 1)
      throw std::invalid_argument("fixed_step_s = " + std::to_string(h) + " s: the scenario's thermal step (" +
                                  std::to_string(st.thermal_step_s) + " s) must be a whole number of fixed steps");
    stepper_.reset();
    spec_ = std::make_unique<components::NetworkSpec>(sc_.spec);
    spec_->settings.integrator.fixed_step_s = h;
    inputs_ = fmu::network_inputs(*spec_);
    cells_.clear();
    for (std::size_t i = 0; i < inputs_.size(); ++i) {
      cells_.push_back(std::make_shared<double>(numbers[i]));
      *inputs_[i].signal = components::Signal::held(cells_.back(), *inputs_[i].signal);
    }
    stepper_ = std::make_unique<components::NetworkStepper>(*spec_, std::numeric_limits<double>::infinity());
    names_.clear();
    channels_ = components::network_channels(*spec_, stepper_->built(), stepper_->wet_index(), names_);
    // Each output's channel (the description lists them in channel order, time_s and inputs left out).
    output_channel_.clear();
    for (std::size_t i = 0; i < model_.variables.size(); ++i) {
      if (model_.variables[i].causality != fmu::Causality::kOutput) continue;
      for (std::size_t c = 0; c < channels_.size(); ++c)
        if (fmu::fmi_name(std::string(channels_[c].name)) == model_.variables[i].name)
          output_channel_.push_back({i, c});
    }
    whole_steps_ = 0.0;
    parameters_changed = false;
    info("network '" + sc_.name + "' built: " + std::to_string(inputs_.size()) + " inputs, " +
         std::to_string(output_channel_.size()) + " outputs, fixed_step_s = " + std::to_string(h) + " s");
  }

  // The master's inputs into the held cells; a change restarts the stepper (`restart`).
  void apply_inputs(bool restart) {
    bool changed = false;
    for (std::size_t i = 0; i < inputs_.size(); ++i)
      if (*cells_[i] != numbers[i]) {
        *cells_[i] = numbers[i];
        changed = true;
      }
    if (!changed) return;
    // A wet clutch reads its clamp force from a schedule in its context, a Haldex coupling's
    // hydraulics a raw pressure setting from one in its command: the held value.
    for (auto& bc : stepper_->built().clutches) {
      if (bc.haldex) {
        if (const auto& p = bc.spec->haldex.valve_pressure_bar)
          bc.command->setting_schedule_bar = components::PiecewiseLinear({0.0}, {std::max((*p)(0.0), 0.0)});
      } else if (bc.wet && bc.context) {
        bc.context->set_normal_force(components::PiecewiseLinear({0.0}, {bc.scheduled_force_N(0.0)}));
      }
    }
    if (restart) stepper_->simulation().restart();
  }

  void update_outputs() {
    const dynamics::Sample s = stepper_->simulation().sample();
    const components::NetworkSlow slow = &stepper_->thermal();
    for (const auto& [i, c] : output_channel_)
      numbers[i] = channels_[c].sampled ? channels_[c].sampled(s) : channels_[c].interpolated(slow);
  }

  io::NetworkScenario sc_;
  fmu::DescribedModel model_;
  std::unique_ptr<components::NetworkSpec> spec_;  // the stepper's spec, inputs held
  std::vector<fmu::NetworkInput> inputs_;          // into spec_, in variable order (vr 0..)
  std::vector<std::shared_ptr<double>> cells_;     // the held inputs' values
  std::unique_ptr<components::NetworkStepper> stepper_;
  std::deque<std::string> names_;
  std::vector<components::NetworkChannel> channels_;
  std::vector<std::pair<std::size_t, std::size_t>> output_channel_;  // (variable, channel)
  double whole_steps_ = 0.0;  // internal steps since the start, on the current grid
};

}  // namespace

namespace shudder::fmu {

std::unique_ptr<InstanceBase> create_instance(const std::string& instance_name, std::string_view guid,
                                              const ResourceLocation& where, const fmi2CallbackFunctions& cb) {
  if (!where.problem.empty()) throw Refusal("the scenario is read from the FMU's resources, but " + where.problem);
  const fs::path index = where.path / kNetworkFmuIndex;
  toml::table t;
  try {
    t = toml::parse_file(index.string());
  } catch (const std::exception& e) {
    throw Refusal("cannot read " + index.string() + " (written by shudder export-fmu): " + e.what());
  }
  const auto scenario = t["scenario"].value<std::string>();
  const auto step = t["fixed_step_s"].value<double>();
  if (!scenario || !step) throw Refusal(index.string() + " needs scenario = \"PATH\" and fixed_step_s = H");
  const fs::path path = where.path / *scenario;
  io::NetworkScenario sc = io::load_network_scenario_text(io::read_scenario_text(path.string()), path.string());
  DescribedModel model = network_description(sc, *step);
  const std::string expected = guid_of(model_description_xml(model));
  if (guid != expected)
    throw Refusal("GUID " + std::string(guid) + " does not match the scenario in the FMU's resources (" + expected +
                  ")");
  return std::make_unique<Instance>(instance_name, cb, where, std::move(sc), std::move(model));
}

}  // namespace shudder::fmu
