// Writes the FMU's modelDescription.xml (FMI 2.0, co-simulation) from fmu/variables.hpp to
// stdout or the file named by argv[1]. Run by CMake when the FMU is packed.
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

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

std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

}  // namespace

int main(int argc, char** argv) {
  std::ostringstream x;
  x << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    << "<fmiModelDescription fmiVersion=\"2.0\" modelName=\"" << escape(kModelName) << "\" guid=\"" << escape(kGuid)
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
    << "    <Category name=\"logStatusError\" description=\"errors: bad parameters, calls out of sequence\"/>\n"
    << "    <Category name=\"logAll\" description=\"every message\"/>\n"
    << "  </LogCategories>\n"
    << "  <DefaultExperiment startTime=\"0\" stepSize=\"0.0001\"/>\n"
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
  x << "  </ModelVariables>\n  <ModelStructure>\n    <Outputs>\n";
  for (int k = 0; k < n_outputs; ++k) x << "      <Unknown index=\"" << output_indices[k] << "\"/>\n";
  x << "    </Outputs>\n    <InitialUnknowns>\n";
  for (int k = 0; k < n_outputs; ++k) x << "      <Unknown index=\"" << output_indices[k] << "\"/>\n";
  x << "    </InitialUnknowns>\n  </ModelStructure>\n</fmiModelDescription>\n";
  if (argc > 1) {
    std::ofstream out(argv[1]);
    out << x.str();
    if (!out) {
      std::cerr << "model_description: cannot write " << argv[1] << "\n";
      return 1;
    }
  } else {
    std::cout << x.str();
  }
  return 0;
}
