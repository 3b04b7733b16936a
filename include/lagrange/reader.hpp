#pragma once
// The YAML model reader (docs/model-language.md): file → Model, with file:line:column errors.

#include <string>

#include "lagrange/model.hpp"

namespace lagrange {

/// Read a model file. Throws ModelError naming file, line, column and what was expected.
Model read_model_file(const std::string& path);

/// Read a model from YAML text; `file_label` is used in error messages.
Model read_model_string(const std::string& yaml_text, const std::string& file_label);

}  // namespace lagrange
