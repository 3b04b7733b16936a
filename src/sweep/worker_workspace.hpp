#pragma once
// A worker's workspace, shared by the pools of threads and of processes.

#include <memory>
#include <optional>

#include "lagrange/dynamics.hpp"
#include "lagrange/sweep.hpp"

namespace lagrange::sweep {

/// A new worker's workspace over `model`, made in `own`, with `options.evaluation` chosen.
Dynamics& worker_workspace(const std::shared_ptr<const CompiledModel>& model,
                           const PoolOptions& options, std::optional<Dynamics>& own);

}  // namespace lagrange::sweep
