#include "sweep/spec_text.hpp"

#include <fmt/format.h>

#include <sstream>

#include "lagrange/reader.hpp"
#include "lagrange/sweep.hpp"

namespace lagrange::sweep {

std::string trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t") - first + 1);
}

std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> out;
  std::string piece;
  std::istringstream in(text);
  while (std::getline(in, piece, sep)) out.push_back(trim(piece));
  if (!text.empty() && text.back() == sep) out.emplace_back();
  return out;
}

double finite_number(const std::string& text, const std::string& context) {
  try {
    return evaluate_value_text(text);
  } catch (const ValueTextError& e) {
    throw StudyError(fmt::format("{}: {}", context, e.what()));
  }
}

std::pair<std::string, std::string> name_and_value(const std::string& spec,
                                                   const std::string& option,
                                                   const std::string& expected) {
  const auto eq = spec.find('=');
  const std::string name = trim(spec.substr(0, eq));
  if (eq == std::string::npos || name.empty())
    throw StudyError(fmt::format("{}: expected {}, got '{}'", option, expected, spec));
  return {name, trim(spec.substr(eq + 1))};
}

}  // namespace lagrange::sweep
