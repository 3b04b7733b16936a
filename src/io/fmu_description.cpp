// modelDescription.xml of an exported FMU (FMI 2.0 §2.2, the layout of fmu_layout.hpp).

#include <fmt/format.h>

#include <algorithm>

#include "io/fmu_layout.hpp"

namespace lagrange::fmu {

namespace {

std::string xml_escape(const std::string& s) {
  std::string out;
  for (char ch : s) {
    switch (ch) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += ch;
    }
  }
  return out;
}

// One <ScalarVariable>: `attributes` are those after valueReference, `real` those of <Real>.
std::string variable(const std::string& name, size_t vr, const std::string& attributes,
                     const std::string& description, const std::string& real) {
  return fmt::format(
      "    <ScalarVariable name=\"{}\" valueReference=\"{}\" {} description=\"{}\">\n"
      "      <Real{}/>\n    </ScalarVariable>\n",
      xml_escape(name), vr, attributes, xml_escape(description), real);
}

std::string start(double value) {
  return fmt::format(" start=\"{:.17g}\"", value);
}

constexpr const char* kState = R"(causality="output" variability="continuous" initial="exact")";
constexpr const char* kCalculated =
    R"(causality="output" variability="continuous" initial="calculated")";
constexpr const char* kLocal = R"(causality="local" variability="continuous" initial="calculated")";
constexpr const char* kParameter = R"(causality="parameter" variability="tunable" initial="exact")";

std::string unknowns(const char* element, const std::vector<size_t>& indices) {
  std::string s = fmt::format("    <{}>\n", element);
  for (size_t i : indices) s += fmt::format("      <Unknown index=\"{}\"/>\n", i);
  return s + fmt::format("    </{}>\n", element);
}

}  // namespace

std::string model_description(const CompiledModel& cm, const Description& d) {
  const Layout vr(cm);
  std::string vars;
  std::vector<size_t> outputs, derivatives, initial;  // 1-based indices = value reference + 1
  for (size_t i = 0; i < cm.nq; ++i) {
    vars += variable(cm.coordinate_names[i], vr.q + i, kState, "coordinate", start(cm.q0[i]));
    outputs.push_back(vr.q + i + 1);
  }
  for (size_t i = 0; i < cm.nv; ++i) {
    vars += variable(cm.velocity_names[i], vr.v + i, kState, "velocity", start(cm.v0[i]));
    outputs.push_back(vr.v + i + 1);
  }
  for (size_t i = 0; i < cm.nq; ++i) {
    vars += variable("der(" + cm.coordinate_names[i] + ")", vr.dq + i, kLocal,
                     "rate of the coordinate", fmt::format(" derivative=\"{}\"", vr.q + i + 1));
    derivatives.push_back(vr.dq + i + 1);
  }
  for (size_t i = 0; i < cm.nv; ++i) {
    vars += variable("der(" + cm.velocity_names[i] + ")", vr.a + i, kLocal,
                     "acceleration (docs/theory.md §4.3)",
                     fmt::format(" derivative=\"{}\"", vr.v + i + 1));
    derivatives.push_back(vr.a + i + 1);
  }
  for (size_t i = 0; i < cm.np; ++i)
    vars += variable(cm.parameter_names[i], vr.p + i, kParameter, "model parameter",
                     start(cm.parameter_defaults[i]));
  for (size_t i = 0; i < cm.k; ++i) {
    const bool external = cm.external_inputs[i];
    vars += variable(cm.input_names[i], vr.u + i,
                     external ? R"(causality="input" variability="continuous")" : kLocal,
                     external ? "external input (follows the model's definition until set)"
                              : "input defined by the model as a function of time",
                     external ? start(d.input_starts[i]) : "");
  }
  for (size_t i = 0; i < cm.m; ++i) {
    vars += variable(cm.constraint_names[i], vr.lambda + i, kCalculated,
                     "constraint multiplier lambda (docs/theory.md §4.3)", "");
    outputs.push_back(vr.lambda + i + 1);
  }
  std::vector<std::string> observed{"kinetic", "potential", "energy"};
  observed.insert(observed.end(), cm.output_names.begin(), cm.output_names.end());
  for (size_t i = 0; i < observed.size(); ++i) {
    vars += variable(observed[i], vr.obs + i, kCalculated,
                     i < 3 ? "kinetic energy T, potential energy U, T + U" : "model output", "");
    outputs.push_back(vr.obs + i + 1);
  }
  vars += variable("fmu.baumgarte_alpha", vr.alpha, kParameter,
                   "Baumgarte rate alpha of the constraint stabilisation (docs/theory.md §4.3)",
                   start(d.alpha));
  vars += variable("fmu.rtol", vr.rtol, kParameter,
                   "relative tolerance of fmi2DoStep's DOP853 integrator", start(d.rtol));
  vars += variable("fmu.atol", vr.atol, kParameter,
                   "absolute tolerance of fmi2DoStep's DOP853 integrator", start(d.atol));
  for (size_t i = 0; i < cm.m + observed.size(); ++i) initial.push_back(vr.lambda + i + 1);
  initial.insert(initial.end(), derivatives.begin(), derivatives.end());
  std::sort(initial.begin(), initial.end());

  const std::string sources =
      "    <SourceFiles>\n      <File name=\"lagrange_fmu.c\"/>\n    </SourceFiles>\n";
  std::string s = fmt::format(
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<fmiModelDescription fmiVersion=\"2.0\" modelName=\"{}\" guid=\"{}\"\n"
      "  description=\"Lagrangian model exported by lagrange (docs/fmu.md)\"\n"
      "  generationTool=\"lagrange\" variableNamingConvention=\"flat\" "
      "numberOfEventIndicators=\"{}\">\n",
      xml_escape(d.model_name), d.guid, cm.stop_when.size());
  if (d.model_exchange)
    s += fmt::format(
        "  <ModelExchange modelIdentifier=\"{}\" canGetAndSetFMUstate=\"true\" "
        "completedIntegratorStepNotNeeded=\"true\">\n{}  </ModelExchange>\n",
        d.identifier, sources);
  if (d.co_simulation)
    s += fmt::format(
        "  <CoSimulation modelIdentifier=\"{}\" canHandleVariableCommunicationStepSize=\"true\" "
        "canGetAndSetFMUstate=\"true\">\n{}  </CoSimulation>\n",
        d.identifier, sources);
  s += "  <LogCategories>\n    <Category name=\"logStatusError\"/>\n"
       "    <Category name=\"logEvents\" description=\"a stop_when condition became true\"/>\n"
       "  </LogCategories>\n";
  s += fmt::format(
      "  <DefaultExperiment startTime=\"0\" stopTime=\"{:.17g}\" tolerance=\"{:.17g}\" "
      "stepSize=\"{:.17g}\"/>\n",
      d.t_end, d.rtol, d.output_step);
  s += "  <ModelVariables>\n" + vars + "  </ModelVariables>\n  <ModelStructure>\n";
  s += unknowns("Outputs", outputs) + unknowns("Derivatives", derivatives) +
       unknowns("InitialUnknowns", initial);
  return s + "  </ModelStructure>\n</fmiModelDescription>\n";
}

}  // namespace lagrange::fmu
