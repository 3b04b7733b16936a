#pragma once
// Size limits that keep a fuzzer inside the reader instead of inside GiNaC: a model goes on to
// derive + compile only when it is small (few coordinates, small expression trees, small powers).

#include <ginac/ginac.h>

#include <cstddef>

#include "lagrange/model.hpp"

namespace lagrange::fuzz {

/// Budget for one model: at most `max_coordinates` coordinates, `max_nodes` expression nodes in
/// total, integer powers of at most `max_exponent` and numbers of at most `max_number` in size.
struct Budget {
  size_t max_coordinates = 3;
  size_t max_nodes = 400;
  double max_exponent = 6;
  double max_number = 1e6;
};

/// True when `model` fits `budget`, so derive + compile finish in milliseconds.
bool fits(const Model& model, const Budget& budget);

}  // namespace lagrange::fuzz
