#pragma once
// The YAML model reader (docs/model-language.md): file → Model, with file:line:column errors.

#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "lagrange/model.hpp"

namespace lagrange {

/// Parameter values that replace the file's (`--set NAME=VALUE`), by parameter name.
using ParameterOverrides = std::map<std::string, double>;

/// An override names no parameter of the model (a mistake of the caller, not of the file).
class ParameterOverrideError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// What a read learns about some parameters (a study's varied ones, `watched`): every use the
/// reader made of their values, so that the model's numbers for other values of them can be had
/// without reading the file again (docs/theory.md §9.4).
struct ReadTrace {
  std::vector<std::string> watched;  ///< in: the parameters whose values are followed
  /// A test the reader made on a value of them (a sign, a range, a warning): `value` (an
  /// expression of the parameters) gave `outcome`.
  struct Check {
    GiNaC::ex value;
    std::function<bool(double)> test;
    bool outcome = false;
  };
  /// A coordinate's initial value (or rate, `rate`) written as an expression of them.
  struct Initial {
    size_t coordinate = 0;
    bool rate = false;
    GiNaC::ex value;
  };
  std::vector<Check> checks;
  std::vector<Initial> initials;
  /// Empty, or the first use of their values the model's numbers cannot be recomputed from (a
  /// tether's shape, a segment count, a body's inertia): then only a new read gives them.
  std::string opaque;
};

/// A value written outside a model file (`--set`, `--initial`, `--vary`, Python) that the model
/// language does not read as a finite number; the message says what and at which character.
class ValueTextError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// `text` read as the model file reads a value (docs/model-language.md): numbers, `pi`, the
/// built-in functions and the `names` given (parameters' values); ValueTextError otherwise.
double evaluate_value_text(const std::string& text,
                           const std::map<std::string, double>& names = {});

/// Start values a caller gives (`--initial`, Python `initial=`), in order: a coordinate's name (a
/// generated one too, `line.node1.x`) or its rate NAME_dot, and the value's text in the model
/// language (numbers, pi, parameters). The reader starts from them, so that what it builds from
/// the start (a tether's nodes) follows; names it does not know are left to the caller.
using StartValues = std::vector<std::pair<std::string, std::string>>;

/// Read a model file. Throws ModelError naming file, line, column and what was expected.
/// `overrides` replace parameter values before anything else is evaluated, so that initial
/// values, checks and settings written as expressions of parameters see them.
Model read_model_file(const std::string& path, const ParameterOverrides& overrides = {});

/// The same, recording in `trace` how the model depends on the values of `trace.watched`.
Model read_model_file(const std::string& path, const ParameterOverrides& overrides,
                      ReadTrace& trace);

/// The same, starting from `start` (ValueTextError, naming the value, for one that does not read).
Model read_model_file(const std::string& path, const ParameterOverrides& overrides,
                      const StartValues& start);

/// Read a model from YAML text; `file_label` is used in error messages.
Model read_model_string(const std::string& yaml_text, const std::string& file_label,
                        const ParameterOverrides& overrides = {}, ReadTrace* trace = nullptr,
                        const StartValues& start = {});

}  // namespace lagrange
