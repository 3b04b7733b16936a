#pragma once
// What fuzz_sweep_spec and fuzz_metric do with one input, shared with their regression test
// (tests/hardening/test_fuzz_regressions.cpp): the text parsed as `lagrange sweep` parses its
// options (docs/sweeps.md), and used when it parses.

#include <string>

namespace lagrange::fuzz {

/// `text` as a `--vary` spec (parse_axis) and as a `--random` spec (parse_random); what parses
/// is expanded into cases by make_cases (a grid of at most 1000 values, three draws). Returns
/// "ok" when either parses and expands, else the StudyError's message; any other exception
/// escapes.
std::string parse_sweep_spec(const std::string& text);

/// `text` as a `--metric` spec (parse_metric), bound to a pendulum's trajectory columns and
/// parameters (bind_metrics) and evaluated over three samples. Returns "ok" or the StudyError's
/// message; any other exception escapes.
std::string evaluate_metric_spec(const std::string& text);

}  // namespace lagrange::fuzz
