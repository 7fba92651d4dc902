// Writes the FMU's modelDescription.xml (FMI 2.0, co-simulation) from fmu/variables.hpp to
// stdout or the file named by argv[1], and, given argv[2], a header defining the GUID for the
// library (the GUID is derived from the description's text, fmu/content_guid.hpp). Run by
// CMake before the library is compiled.
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

#include "fmu/content_guid.hpp"
#include "fmu/variables.hpp"

namespace {

using namespace shudder::fmu;

std::string escape(std::string_view s) {
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

// The shortest of %.15g and %.17g that reads back as the same double.
std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.15g", x);
  if (std::strtod(buf, nullptr) != x) std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

}  // namespace

int main(int argc, char** argv) {
  std::ostringstream x;
  x << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    << "<fmiModelDescription fmiVersion=\"2.0\" modelName=\"" << escape(kModelName) << "\" guid=\"" << kGuidPlaceholder
    << "\"\n    description=\"Wet clutch with its thermal field, prescribed slip, fixed-step (shudder)\""
    << " generationTool=\"shudder " << SHUDDER_VERSION << "\" variableNamingConvention=\"flat\""
    << " numberOfEventIndicators=\"0\">\n"
    << "  <CoSimulation modelIdentifier=\"" << escape(kModelIdentifier) << "\" canHandleVariableCommunicationStepSize=\"true\""
    << " canInterpolateInputs=\"false\" maxOutputDerivativeOrder=\"0\" canRunAsynchronuously=\"false\""
    << " canBeInstantiatedOnlyOncePerProcess=\"false\" canNotUseMemoryManagementFunctions=\"true\""
    << " canGetAndSetFMUstate=\"false\" canSerializeFMUstate=\"false\"/>\n"
    << "  <UnitDefinitions>\n"
    << "    <Unit name=\"rad/s\"><BaseUnit s=\"-1\" rad=\"1\"/></Unit>\n"
    << "    <Unit name=\"N\"><BaseUnit kg=\"1\" m=\"1\" s=\"-2\"/></Unit>\n"
    << "    <Unit name=\"N.m\"><BaseUnit kg=\"1\" m=\"2\" s=\"-2\"/></Unit>\n"
    << "    <Unit name=\"Pa\"><BaseUnit kg=\"1\" m=\"-1\" s=\"-2\"/></Unit>\n"
    << "    <Unit name=\"W\"><BaseUnit kg=\"1\" m=\"2\" s=\"-3\"/></Unit>\n"
    << "    <Unit name=\"degC\"><BaseUnit K=\"1\" offset=\"273.15\"/></Unit>\n"
    << "    <Unit name=\"mm\"><BaseUnit m=\"1\" factor=\"0.001\"/></Unit>\n"
    << "    <Unit name=\"m2\"><BaseUnit m=\"2\"/></Unit>\n"
    << "    <Unit name=\"s\"><BaseUnit s=\"1\"/></Unit>\n"
    << "    <Unit name=\"ml/min\"><BaseUnit m=\"3\" s=\"-1\" factor=\"1.6666666666666667e-08\"/></Unit>\n"
    << "    <Unit name=\"1\"><BaseUnit/></Unit>\n"
    << "  </UnitDefinitions>\n"
    << "  <LogCategories>\n"
    << "    <Category name=\"logEvents\" description=\"what the instance does: instantiation, parameters, fluid"
       " loaded, initialisation, steps that end with a shorter internal step, reset, termination\"/>\n"
    << "    <Category name=\"logStatusWarning\" description=\"warnings: an unknown log category\"/>\n"
    << "    <Category name=\"logStatusDiscard\" description=\"status queries this FMU does not answer\"/>\n"
    << "    <Category name=\"logStatusError\" description=\"errors: bad parameters, calls out of sequence\"/>\n"
    << "    <Category name=\"logAll\" description=\"every message\"/>\n"
    << "  </LogCategories>\n"
    << "  <DefaultExperiment startTime=\"0\" stopTime=\"" << number(kDefaultStopTime_s) << "\" stepSize=\""
    << number(kDefaultStepSize_s) << "\"/>\n"
    << "  <ModelVariables>\n";
  int index = 0, output_indices[64], n_outputs = 0;
  for (const Variable& v : kVariables) {
    ++index;
    const char* causality = v.causality == kParameter ? "parameter" : v.causality == kInput ? "input" : "output";
    const char* variability = v.causality == kParameter ? "fixed" : v.type == kReal ? "continuous" : "discrete";
    x << "    <!-- index " << index << " -->\n"
      << "    <ScalarVariable name=\"" << escape(v.name) << "\" valueReference=\"" << v.vr << "\" causality=\""
      << causality << "\" variability=\"" << variability << "\" description=\"" << escape(v.description) << "\">\n";
    const bool has_start = v.causality != kOutput;
    switch (v.type) {
      case kReal:
        x << "      <Real";
        if (!v.unit.empty()) x << " unit=\"" << escape(v.unit) << "\"";
        if (has_start) x << " start=\"" << number(v.start) << "\"";
        x << "/>\n";
        break;
      case kInteger:
        x << "      <Integer start=\"" << static_cast<long>(v.start) << "\"/>\n";
        break;
      case kBoolean:
        x << "      <Boolean start=\"" << (v.start != 0.0 ? "true" : "false") << "\"/>\n";
        break;
      case kString:
        x << "      <String start=\"" << escape(v.start_text) << "\"/>\n";
        break;
    }
    x << "    </ScalarVariable>\n";
    if (v.causality == kOutput) output_indices[n_outputs++] = index;
  }
  // Outputs at communication points are the values over the step just taken: setting an input
  // afterwards does not change them (no direct feedthrough), so they depend on no input and a
  // master may feed the torque back into the speeds without an algebraic loop. In
  // initialisation mode they are computed from the current inputs and parameters: the
  // InitialUnknowns carry no dependency list (they depend on every known).
  x << "  </ModelVariables>\n  <ModelStructure>\n    <Outputs>\n";
  for (int k = 0; k < n_outputs; ++k) x << "      <Unknown index=\"" << output_indices[k] << "\" dependencies=\"\"/>\n";
  x << "    </Outputs>\n    <InitialUnknowns>\n";
  for (int k = 0; k < n_outputs; ++k) x << "      <Unknown index=\"" << output_indices[k] << "\"/>\n";
  x << "    </InitialUnknowns>\n  </ModelStructure>\n</fmiModelDescription>\n";
  std::string text = x.str();
  const std::string guid = content_guid(text);
  text.replace(text.find(kGuidPlaceholder), kGuidPlaceholder.size(), guid);
  if (argc > 1) {
    std::ofstream out(argv[1]);
    out << text;
    if (!out) {
      std::cerr << "model_description: cannot write " << argv[1] << "\n";
      return 1;
    }
  } else {
    std::cout << text;
  }
  if (argc > 2) {
    std::ofstream header(argv[2]);
    header << "#pragma once\n// Generated by fmu/model_description.cpp: the GUID of the modelDescription.xml written with it.\n"
           << "#include <string_view>\nnamespace shudder::fmu {\ninline constexpr std::string_view kGuid = \"" << guid
           << "\";\n}  // namespace shudder::fmu\n";
    if (!header) {
      std::cerr << "model_description: cannot write " << argv[2] << "\n";
      return 1;
    }
  }
  return 0;
}
