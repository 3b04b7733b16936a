// `optimal_control: stages:` (docs/model-language.md, "Homotopy stages"): the problems solved
// before the problem itself, each a change of its objective, of its controls' bounds, a tracking
// weight and Ipopt options, checked with located errors.

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "model/model_reader.hpp"

namespace lagrange::model {

void ModelReader::read_stages(const YAML::Node& node, OptimalControlSpec& spec) const {
  expect_seq(node,
             "stages (a list of {name, minimize or maximize, controls, horizon, track, ipopt})");
  for (const YAML::Node& item : node) {
    expect_map(item, "a stage ({name, minimize or maximize, controls, horizon, track, ipopt})");
    check_keys(item, {"name", "minimize", "maximize", "controls", "horizon", "track", "ipopt"},
               "a stage");
    StageSpec stage;
    stage.loc = src_.at(item);
    if (!item["name"]) fail(item, "expected 'name' in a stage, got none");
    stage.name = scalar(item["name"], "a stage's name");
    for (const StageSpec& s : spec.stages)
      if (s.name == stage.name)
        fail(item["name"], fmt::format("expected stage names used once, got '{}' twice (the "
                                       "first at {})",
                                       clip(stage.name), s.loc.str()));
    const std::string what = fmt::format("stage '{}'", stage.name);
    if (item["minimize"] && item["maximize"])
      fail(item["maximize"],
           fmt::format("expected one of 'minimize' and 'maximize' in {}, got both", what));
    if (item["minimize"] || item["maximize"]) {
      OptimalControlSpec objective;
      objective.maximize = static_cast<bool>(item["maximize"]);
      read_objective(item[objective.maximize ? "maximize" : "minimize"], objective);
      stage.replaces_objective = true;
      stage.maximize = objective.maximize;
      stage.integrand = objective.integrand;
      stage.terminal = objective.terminal;
      stage.mean_integrand = objective.mean_integrand;
      stage.objective_text = objective.objective_text;
    }
    if (const YAML::Node c = item["controls"]; c && !c.IsNull()) {
      expect_map(
          c, fmt::format("the controls of {} (a map CONTROL: value or {{lower, upper}})", what));
      for (const auto& kv : c) {
        const std::string name = scalar(kv.first, "a control of " + what);
        const auto control =
            std::find_if(spec.controls.begin(), spec.controls.end(),
                         [&](const ControlSpec& s) { return m_.inputs.at(s.input).name == name; });
        if (control == spec.controls.end()) {
          std::string controls;
          for (const ControlSpec& s : spec.controls)
            controls += (controls.empty() ? "" : ", ") + m_.inputs.at(s.input).name;
          fail(kv.first, fmt::format("expected a control of the problem in {}, got '{}' "
                                     "(controls: {})",
                                     what, clip(name), controls));
        }
        const std::string bound = fmt::format("control '{}' in {}", name, what);
        Bounds b;
        if (kv.second.IsMap()) {
          b = read_bounds(kv.second, bound);
        } else {
          b.lower = b.upper = number(kv.second, kParams, bound);
        }
        stage.control_bounds.emplace_back(static_cast<size_t>(control - spec.controls.begin()), b);
      }
    }
    if (const YAML::Node h = item["horizon"]; h && !h.IsNull()) {
      if (!spec.free_horizon)
        fail(h, fmt::format("expected the horizon of {} only with a free horizon in the problem "
                            "(horizon: {{lower, upper}}), got a fixed T = {:g}",
                            what, spec.horizon));
      Bounds b;
      if (h.IsMap()) {
        b = read_bounds(h, "the horizon of " + what);
      } else {
        b.lower = b.upper = number(h, kParams, "the horizon of " + what);
      }
      if (!(b.lower > 0) || !std::isfinite(b.upper))
        fail(h, fmt::format("expected the horizon of {} with 0 < lower <= upper < inf, got "
                            "[{:g}, {:g}]",
                            what, b.lower, b.upper));
      stage.horizon = b;
    }
    if (item["track"]) {
      stage.track = number(item["track"], kParams, "track of " + what);
      if (!(stage.track >= 0) || !std::isfinite(stage.track))
        fail(item["track"], fmt::format("expected track >= 0 in {} (the weight of the states' "
                                        "distance from the stage's start), got {:g}",
                                        what, stage.track));
    }
    if (const YAML::Node o = item["ipopt"]; o && !o.IsNull()) {
      expect_map(o, fmt::format("the ipopt options of {} (a map OPTION: value)", what));
      for (const auto& kv : o)
        stage.ipopt.emplace_back(scalar(kv.first, "an Ipopt option of " + what),
                                 scalar(kv.second, "the value of an Ipopt option of " + what));
    }
    if (!stage.replaces_objective && stage.control_bounds.empty() && stage.track == 0 &&
        stage.ipopt.empty() && !stage.horizon)
      fail(item, fmt::format("expected {} to change the problem (minimize or maximize, controls, "
                             "horizon, track or ipopt), got only its name",
                             what));
    spec.stages.push_back(std::move(stage));
  }
}

}  // namespace lagrange::model
