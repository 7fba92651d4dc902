#pragma once
// modelDescription.xml (FMI 2.0, co-simulation) of a shudder FMU from its variables, with the
// content GUID in place (fmu/content_guid.hpp): one writer for the clutch FMU's description,
// written at build time (fmu/model_description.cpp), and for a network's, written by
// `shudder export-fmu` and written again by the network FMU's library at instantiation to check
// the GUID it is given (fmu/network_fmu.cpp) — both sides produce the same text from the same
// scenario, so a description cannot be paired with other resources.
//
// Capabilities: any communication step size, no input interpolation, no FMU state. Units: the
// UnitDefinitions list the units the variables use, from the table below. ModelStructure: every
// output depends on no input at communication points (the values over the step just taken),
// and as an initial unknown on every known (no dependency list).
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "fmu/content_guid.hpp"
#include "fmu/fmi2_instance.hpp"

namespace shudder::fmu {

struct DescribedVariable {
  unsigned vr = 0;
  std::string name;
  Type type = Type::kReal;
  Causality causality = Causality::kOutput;
  std::string unit;  // "" for none
  double start = 0.0;
  std::string start_text;
  std::string description;
};

struct DescribedModel {
  std::string model_name, model_identifier, description;
  std::string naming_convention = "flat";  // or "structured"
  std::string log_events;                  // what the logEvents category reports
  double start_time_s = 0.0, stop_time_s = 1.0, step_size_s = 1e-4;
  std::vector<DescribedVariable> variables;
};

/// The units a description may use and their SI base (FMI 2.0 section 2.2.2).
struct KnownUnit {
  std::string_view name, base;
};
inline constexpr KnownUnit kKnownUnits[] = {
    {"rad/s", "s=\"-1\" rad=\"1\""},
    {"rpm", "s=\"-1\" rad=\"1\" factor=\"0.10471975511965977\""},
    {"km/h", "m=\"1\" s=\"-1\" factor=\"0.27777777777777779\""},
    {"N", "kg=\"1\" m=\"1\" s=\"-2\""},
    {"N.m", "kg=\"1\" m=\"2\" s=\"-2\""},
    {"Pa", "kg=\"1\" m=\"-1\" s=\"-2\""},
    {"bar", "kg=\"1\" m=\"-1\" s=\"-2\" factor=\"100000\""},
    {"W", "kg=\"1\" m=\"2\" s=\"-3\""},
    {"degC", "K=\"1\" offset=\"273.15\""},
    {"mm", "m=\"1\" factor=\"0.001\""},
    {"m2", "m=\"2\""},
    {"s", "s=\"1\""},
    {"ml/min", "m=\"3\" s=\"-1\" factor=\"1.6666666666666667e-08\""},
    {"1", ""},
};

inline std::string xml_escape(std::string_view s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

/// The shortest of %.15g and %.17g that reads back as the same double.
inline std::string xml_number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.15g", x);
  if (std::strtod(buf, nullptr) != x) std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

/// The description's text with its content GUID; throws std::invalid_argument for a unit
/// outside kKnownUnits.
inline std::string model_description_xml(const DescribedModel& m) {
  for (const auto& v : m.variables) {
    bool known = v.unit.empty();
    for (const auto& u : kKnownUnits) known = known || u.name == v.unit;
    if (!known) throw std::invalid_argument("variable " + v.name + ": unit '" + v.unit + "' has no definition");
  }
  std::ostringstream x;
  x << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    << "<fmiModelDescription fmiVersion=\"2.0\" modelName=\"" << xml_escape(m.model_name) << "\" guid=\""
    << kGuidPlaceholder << "\"\n    description=\"" << xml_escape(m.description) << "\""
    << " generationTool=\"shudder " << SHUDDER_VERSION << "\" variableNamingConvention=\"" << m.naming_convention
    << "\" numberOfEventIndicators=\"0\">\n"
    << "  <CoSimulation modelIdentifier=\"" << xml_escape(m.model_identifier)
    << "\" canHandleVariableCommunicationStepSize=\"true\""
    << " canInterpolateInputs=\"false\" maxOutputDerivativeOrder=\"0\" canRunAsynchronuously=\"false\""
    << " canBeInstantiatedOnlyOncePerProcess=\"false\" canNotUseMemoryManagementFunctions=\"true\""
    << " canGetAndSetFMUstate=\"false\" canSerializeFMUstate=\"false\"/>\n"
    << "  <UnitDefinitions>\n";
  for (const auto& u : kKnownUnits) {
    bool used = false;
    for (const auto& v : m.variables) used = used || v.unit == u.name;
    if (used)
      x << "    <Unit name=\"" << xml_escape(u.name) << "\"><BaseUnit" << (u.base.empty() ? "" : " ") << u.base
        << "/></Unit>\n";
  }
  x << "  </UnitDefinitions>\n"
    << "  <LogCategories>\n"
    << "    <Category name=\"logEvents\" description=\"" << xml_escape(m.log_events) << "\"/>\n"
    << "    <Category name=\"logStatusWarning\" description=\"warnings: an unknown log category\"/>\n"
    << "    <Category name=\"logStatusDiscard\" description=\"status queries this FMU does not answer\"/>\n"
    << "    <Category name=\"logStatusError\" description=\"errors: bad parameters, calls out of sequence\"/>\n"
    << "    <Category name=\"logAll\" description=\"every message\"/>\n"
    << "  </LogCategories>\n"
    << "  <DefaultExperiment startTime=\"" << xml_number(m.start_time_s) << "\" stopTime=\""
    << xml_number(m.stop_time_s) << "\" stepSize=\"" << xml_number(m.step_size_s) << "\"/>\n"
    << "  <ModelVariables>\n";
  int index = 0;
  std::vector<int> output_indices;
  for (const auto& v : m.variables) {
    ++index;
    const bool parameter = v.causality == Causality::kParameter;
    const char* causality = parameter ? "parameter" : v.causality == Causality::kInput ? "input" : "output";
    const char* variability = parameter ? "fixed" : v.type == Type::kReal ? "continuous" : "discrete";
    x << "    <!-- index " << index << " -->\n"
      << "    <ScalarVariable name=\"" << xml_escape(v.name) << "\" valueReference=\"" << v.vr << "\" causality=\""
      << causality << "\" variability=\"" << variability << "\" description=\"" << xml_escape(v.description) << "\">\n";
    const bool has_start = v.causality != Causality::kOutput;
    switch (v.type) {
      case Type::kReal:
        x << "      <Real";
        if (!v.unit.empty()) x << " unit=\"" << xml_escape(v.unit) << "\"";
        if (has_start) x << " start=\"" << xml_number(v.start) << "\"";
        x << "/>\n";
        break;
      case Type::kInteger: x << "      <Integer start=\"" << static_cast<long>(v.start) << "\"/>\n"; break;
      case Type::kBoolean: x << "      <Boolean start=\"" << (v.start != 0.0 ? "true" : "false") << "\"/>\n"; break;
      case Type::kString: x << "      <String start=\"" << xml_escape(v.start_text) << "\"/>\n"; break;
    }
    x << "    </ScalarVariable>\n";
    if (v.causality == Causality::kOutput) output_indices.push_back(index);
  }
  // Outputs at communication points are the values over the step just taken: setting an input
  // afterwards does not change them (no direct feedthrough), so they depend on no input and a
  // master may feed them back into the inputs without an algebraic loop. In initialisation
  // mode they are computed from the current inputs and parameters: the InitialUnknowns carry
  // no dependency list (they depend on every known).
  x << "  </ModelVariables>\n  <ModelStructure>\n    <Outputs>\n";
  for (int i : output_indices) x << "      <Unknown index=\"" << i << "\" dependencies=\"\"/>\n";
  x << "    </Outputs>\n    <InitialUnknowns>\n";
  for (int i : output_indices) x << "      <Unknown index=\"" << i << "\"/>\n";
  x << "    </InitialUnknowns>\n  </ModelStructure>\n</fmiModelDescription>\n";
  std::string text = x.str();
  const std::string guid = content_guid(text);
  text.replace(text.find(kGuidPlaceholder), kGuidPlaceholder.size(), guid);
  return text;
}

/// The GUID attribute of a description written by model_description_xml.
inline std::string guid_of(const std::string& xml) {
  const auto a = xml.find("guid=\"") + 6;
  return xml.substr(a, xml.find('"', a) - a);
}

}  // namespace shudder::fmu
