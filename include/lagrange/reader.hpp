#pragma once
// The YAML model reader (docs/model-language.md): file → Model, with file:line:column errors.

#include <map>
#include <stdexcept>
#include <string>

#include "lagrange/model.hpp"

namespace lagrange {

/// Parameter values that replace the file's (`--set NAME=VALUE`), by parameter name.
using ParameterOverrides = std::map<std::string, double>;

/// An override names no parameter of the model (a mistake of the caller, not of the file).
class ParameterOverrideError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// Read a model file. Throws ModelError naming file, line, column and what was expected.
/// `overrides` replace parameter values before anything else is evaluated, so that initial
/// values, checks and settings written as expressions of parameters see them.
Model read_model_file(const std::string& path, const ParameterOverrides& overrides = {});

/// Read a model from YAML text; `file_label` is used in error messages.
Model read_model_string(const std::string& yaml_text, const std::string& file_label,
                        const ParameterOverrides& overrides = {});

}  // namespace lagrange
