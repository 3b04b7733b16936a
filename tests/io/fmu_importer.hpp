#pragma once
// A small FMI 2.0 importer for the tests, doing what an importer does: unzip the FMU (with
// Info-ZIP's unzip, a reader we did not write), read modelDescription.xml (tinyxml2), dlopen
// binaries/linux64/<modelIdentifier>.so and look up the FMI functions.

#include <dlfcn.h>
#include <fmi2Functions.h>
#include <tinyxml2.h>

#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace lagrange::testing {

/// Messages an FMU sent to its logger, per instance (the environment pointer).
struct FmuLog {
  std::vector<std::string> messages;
};

inline void fmu_logger(fmi2ComponentEnvironment env, fmi2String, fmi2Status, fmi2String,
                       fmi2String message, ...) {
  char text[1024];
  va_list args;
  va_start(args, message);
  std::vsnprintf(text, sizeof text, message, args);
  va_end(args);
  static_cast<FmuLog*>(env)->messages.emplace_back(text);
}

class FmuImporter {
 public:
  /// Unzips `fmu` into `dir` (emptied first), reads the description and loads the binary.
  FmuImporter(const std::filesystem::path& fmu, const std::filesystem::path& dir) : dir_(dir) {
    std::filesystem::remove_all(dir);
    const std::string cmd = "unzip -q -o '" + fmu.string() + "' -d '" + dir.string() + "'";
    if (std::system(cmd.c_str()) != 0) throw std::runtime_error("unzip failed: " + cmd);
    tinyxml2::XMLDocument doc;
    if (doc.LoadFile((dir / "modelDescription.xml").c_str()) != tinyxml2::XML_SUCCESS)
      throw std::runtime_error("modelDescription.xml does not parse");
    const tinyxml2::XMLElement* root = doc.FirstChildElement("fmiModelDescription");
    guid = root->Attribute("guid");
    event_indicators = root->UnsignedAttribute("numberOfEventIndicators");
    for (const char* kind : {"CoSimulation", "ModelExchange"})
      if (const tinyxml2::XMLElement* e = root->FirstChildElement(kind))
        identifier = e->Attribute("modelIdentifier");
    const tinyxml2::XMLElement* vars = root->FirstChildElement("ModelVariables");
    for (const tinyxml2::XMLElement* v = vars->FirstChildElement("ScalarVariable"); v;
         v = v->NextSiblingElement("ScalarVariable")) {
      Variable var{v->UnsignedAttribute("valueReference"), v->Attribute("causality"),
                   v->FirstChildElement("Real")->DoubleAttribute("start", NAN)};
      variables[v->Attribute("name")] = var;
      order.push_back(v->Attribute("name"));
    }
    for (const char* list : {"Outputs", "Derivatives", "InitialUnknowns"})
      for (const tinyxml2::XMLElement* u = root->FirstChildElement("ModelStructure")
                                               ->FirstChildElement(list)
                                               ->FirstChildElement("Unknown");
           u; u = u->NextSiblingElement("Unknown"))
        structure[list].push_back(u->UnsignedAttribute("index"));
    library = (dir / "binaries" / "linux64" / (identifier + ".so")).string();
    handle_ = dlopen(library.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle_) throw std::runtime_error(std::string("dlopen: ") + dlerror());
    load(instantiate, "fmi2Instantiate");
    load(free_instance, "fmi2FreeInstance");
    load(setup, "fmi2SetupExperiment");
    load(enter_init, "fmi2EnterInitializationMode");
    load(exit_init, "fmi2ExitInitializationMode");
    load(do_step, "fmi2DoStep");
    load(get_real, "fmi2GetReal");
    load(set_real, "fmi2SetReal");
    load(set_time, "fmi2SetTime");
    load(set_states, "fmi2SetContinuousStates");
    load(get_derivatives, "fmi2GetDerivatives");
    load(enter_continuous, "fmi2EnterContinuousTimeMode");
    load(enter_event_mode, "fmi2EnterEventMode");
    load(get_event_indicators, "fmi2GetEventIndicators");
    load(get_real_status, "fmi2GetRealStatus");
    load(get_boolean_status, "fmi2GetBooleanStatus");
    load(new_discrete_states, "fmi2NewDiscreteStates");
    load(get_state, "fmi2GetFMUstate");
    load(set_state, "fmi2SetFMUstate");
    load(free_state, "fmi2FreeFMUstate");
    load(reset, "fmi2Reset");
    load(terminate, "fmi2Terminate");
  }
  ~FmuImporter() {
    if (handle_) dlclose(handle_);
  }
  FmuImporter(const FmuImporter&) = delete;
  FmuImporter& operator=(const FmuImporter&) = delete;

  struct Variable {
    fmi2ValueReference vr = 0;
    std::string causality;
    double start = NAN;
  };

  fmi2ValueReference vr(const std::string& name) const {
    auto it = variables.find(name);
    if (it == variables.end()) throw std::out_of_range("no FMU variable " + name);
    return it->second.vr;
  }

  /// An instance logging into `log`; nullptr when fmi2Instantiate refuses.
  fmi2Component make(fmi2Type type, FmuLog& log, const char* name = "test",
                     const std::string& guid_given = "") {
    owned_.push_back(std::make_unique<fmi2CallbackFunctions>(
        fmi2CallbackFunctions{fmu_logger, std::calloc, std::free, nullptr, &log}));
    return instantiate(name, type, guid_given.empty() ? guid.c_str() : guid_given.c_str(), "",
                       owned_.back().get(), fmi2False, fmi2False);
  }

  double get(fmi2Component c, const std::string& name) const {
    const fmi2ValueReference r = vr(name);
    double x = NAN;
    if (get_real(c, &r, 1, &x) != fmi2OK) throw std::runtime_error("fmi2GetReal " + name);
    return x;
  }
  fmi2Status set(fmi2Component c, const std::string& name, double value) const {
    const fmi2ValueReference r = vr(name);
    return set_real(c, &r, 1, &value);
  }

  std::string guid, identifier, library;
  unsigned event_indicators = 0;  ///< numberOfEventIndicators
  std::map<std::string, Variable> variables;
  std::vector<std::string> order;  ///< names in the description's order (index − 1)
  std::map<std::string, std::vector<unsigned>> structure;

  fmi2InstantiateTYPE* instantiate = nullptr;
  fmi2FreeInstanceTYPE* free_instance = nullptr;
  fmi2SetupExperimentTYPE* setup = nullptr;
  fmi2EnterInitializationModeTYPE* enter_init = nullptr;
  fmi2ExitInitializationModeTYPE* exit_init = nullptr;
  fmi2DoStepTYPE* do_step = nullptr;
  fmi2GetRealTYPE* get_real = nullptr;
  fmi2SetRealTYPE* set_real = nullptr;
  fmi2SetTimeTYPE* set_time = nullptr;
  fmi2SetContinuousStatesTYPE* set_states = nullptr;
  fmi2GetDerivativesTYPE* get_derivatives = nullptr;
  fmi2EnterContinuousTimeModeTYPE* enter_continuous = nullptr;
  fmi2EnterEventModeTYPE* enter_event_mode = nullptr;
  fmi2GetEventIndicatorsTYPE* get_event_indicators = nullptr;
  fmi2GetRealStatusTYPE* get_real_status = nullptr;
  fmi2GetBooleanStatusTYPE* get_boolean_status = nullptr;
  fmi2NewDiscreteStatesTYPE* new_discrete_states = nullptr;
  fmi2GetFMUstateTYPE* get_state = nullptr;
  fmi2SetFMUstateTYPE* set_state = nullptr;
  fmi2FreeFMUstateTYPE* free_state = nullptr;
  fmi2ResetTYPE* reset = nullptr;
  fmi2TerminateTYPE* terminate = nullptr;

 private:
  template <class F>
  void load(F*& f, const char* name) {
    f = reinterpret_cast<F*>(dlsym(handle_, name));
    if (!f) throw std::runtime_error(std::string("the FMU does not export ") + name);
  }
  std::filesystem::path dir_;
  void* handle_ = nullptr;
  std::vector<std::unique_ptr<fmi2CallbackFunctions>> owned_;
};

}  // namespace lagrange::testing
