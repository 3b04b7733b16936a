#pragma once
// Driven guides of the report's 3-D view: a point moved both by a drive (t or an input) and by
// one angle coordinate — a bead on a turning hoop — rides on the curve its angle sweeps at the
// drive's current state, and the view draws that curve moving with the drive.

#include <ginac/ginac.h>

#include <vector>

#include "lagrange/model.hpp"

namespace lagrange::io {

/// Candidate guides: per point, the position at kSamples + 1 values of its angle over a full
/// turn (the last one closes the turn), 3 numbers each.
struct DrivenGuides {
  static constexpr size_t kSamples = 48;
  std::vector<size_t> point;  ///< index into the points given
  std::vector<GiNaC::ex> outputs;
};

/// The guides of `points` that depend on t or an input and on exactly one of the coordinates
/// `q`; whether the curve closes (the coordinate is an angle) is for the caller to see from the
/// numbers.
DrivenGuides driven_guides(const Model& model, const std::vector<const Point*>& points,
                           const std::vector<GiNaC::symbol>& q);

}  // namespace lagrange::io
