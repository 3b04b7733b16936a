#pragma once
// Error types shared by every stage: user mistakes carry a source location.

#include <stdexcept>
#include <string>

namespace lagrange {

/// A position in a model file (1-based line and column; 0 when unknown).
struct SourceLoc {
  std::string file;
  int line = 0;
  int column = 0;
  /// "file:line:column" (or as much of it as is known).
  std::string str() const;
};

/// A mistake in a model: the message reads "file:line:column: error: what, expected …".
class ModelError : public std::runtime_error {
 public:
  ModelError(const SourceLoc& loc, const std::string& what);
  const SourceLoc& loc() const { return loc_; }
  /// The message without the location prefix.
  const std::string& detail() const { return detail_; }

 private:
  SourceLoc loc_;
  std::string detail_;
};

/// A numerical failure during simulation (singular mass matrix, integrator gave up, NaN).
class SimulationError : public std::runtime_error {
 public:
  SimulationError(double t, const std::string& what);
  double time() const { return t_; }

 private:
  double t_;
};

}  // namespace lagrange
