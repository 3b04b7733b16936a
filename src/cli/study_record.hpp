#pragma once
// STUDY/study.txt (docs/sweeps.md, "Workers, progress and interruptions"): what decides a
// study's cases and rows — the options, the model file's and its equations' SHA-256 and every
// metric — so that --resume refuses to mix another study into a summary, naming what changed.

#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "lagrange/compiled_model.hpp"
#include "lagrange/sweep.hpp"

namespace lagrange::cli {

/// The record of the study `opt` describes, one item a line: the options that decide the cases
/// and their rows, the SHA-256 of the bytes of `opt.model` and of `cm`'s tapes (equations read
/// from other files, such as a URDF, included), and `metrics` as bound (the model file's too).
std::string study_record(const Options& opt, const CompiledModel& cm,
                         const std::vector<sweep::Metric>& metrics);

/// The lines of record `was` missing from `now` ("  was: …") and those of `now` missing from
/// `was` ("  now: …"), in their order; empty when the two hold the same lines.
std::string record_changes(const std::string& was, const std::string& now);

}  // namespace lagrange::cli
