#pragma once
// LaTeX spellings of user names: theta1 → \theta_{1}, with \dot / \ddot for derivatives.

#include <string>

namespace lagrange::model {

/// LaTeX for `name`, optionally decorated ("\\dot", "\\ddot"): "theta1", "\\dot" →
/// "\\dot{\\theta}_{1}".
std::string latex_name(const std::string& name, const std::string& accent = "");

}  // namespace lagrange::model
