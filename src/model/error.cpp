#include "lagrange/error.hpp"

#include <fmt/format.h>

namespace lagrange {

std::string SourceLoc::str() const {
  std::string s = file.empty() ? std::string("<input>") : file;
  if (line > 0) s += fmt::format(":{}", line);
  if (line > 0 && column > 0) s += fmt::format(":{}", column);
  return s;
}

ModelError::ModelError(const SourceLoc& loc, const std::string& what)
    : std::runtime_error(fmt::format("{}: error: {}", loc.str(), what)), loc_(loc), detail_(what) {}

SimulationError::SimulationError(double t, const std::string& what)
    : std::runtime_error(fmt::format("simulation failed at t = {:.17g}: {}", t, what)), t_(t) {}

}  // namespace lagrange
