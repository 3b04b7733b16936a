// The workers of a study on one machine: threads that each own a Dynamics over the shared,
// immutable compiled model and take the next case when they finish one, reading it first when
// the caller reads cases on the workers (the caller's read guards what is not thread-safe).

#include <malloc.h>

#include <atomic>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>

#include "lagrange/dynamics.hpp"
#include "lagrange/sweep.hpp"
#include "sweep/worker_workspace.hpp"

namespace lagrange::sweep {

// A case allocates and frees the same blocks as the one before it (trajectory, integrator
// state). glibc would hand the large ones back to the kernel after every case (munmap, heap
// trimming) and fault them in again for the next: page faults and, with two workers, TLB
// shootdowns between their cores, 20-25 % of the kite's cpu. Kept, the memory stays at what one
// case per worker needs.
void keep_freed_memory() {
  mallopt(M_MMAP_THRESHOLD, 32 << 20);  // glibc's largest
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
}

Dynamics& worker_workspace(const std::shared_ptr<const CompiledModel>& model,
                           const PoolOptions& options, std::optional<Dynamics>& own) {
  own.emplace(model, model->parameter_defaults);
  if (options.evaluation != Evaluation::Interpreter) own->set_evaluation(options.evaluation);
  return *own;
}

void run_pool(const std::shared_ptr<const CompiledModel>& model,
              const std::vector<CaseInput>& inputs, const std::vector<size_t>& pending,
              const std::vector<Metric>& metrics, const PoolOptions& options) {
  std::atomic<size_t> next{0};
  std::mutex report;
  std::exception_ptr error;  // the first exception of a worker (a summary that cannot be written)
  std::atomic<bool> failed{false};
  const auto stopped = [&] { return failed || (options.interrupt && options.interrupt->load()); };
  const auto work = [&](bool calling_thread) {
    try {
      // Dynamics holds the specialised tapes and all scratch memory: one per worker.
      std::optional<Dynamics> own;
      Dynamics& dyn = calling_thread && options.workspace ? *options.workspace
                                                          : worker_workspace(model, options, own);
      Trajectory traj;
      for (size_t slot = next++; slot < pending.size() && !stopped(); slot = next++) {
        const size_t index = pending[slot];
        CaseRead read;
        if (options.read) {
          read = options.read(index);
        } else {
          read.input = inputs[index];
        }
        if (read.input) read.input->options.interrupt = options.interrupt;
        CaseResult result = run_case(dyn, read, metrics, options.keep ? &traj : nullptr);
        result.index = index;
        result.read_seconds = read.read_seconds;
        if (result.status == Trajectory::Status::Interrupted) break;
        const std::lock_guard<std::mutex> lock(report);
        if (options.keep && read.input) options.keep(index, traj);
        if (options.done) options.done(result);
      }
    } catch (...) {
      const std::lock_guard<std::mutex> lock(report);
      if (!error) error = std::current_exception();
      failed = true;
    }
  };
  const size_t n = std::max<size_t>(1, std::min(options.workers, pending.size()));
  std::vector<std::thread> threads;
  for (size_t i = 1; i < n; ++i) threads.emplace_back(work, false);
  work(true);
  for (auto& t : threads) t.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace lagrange::sweep
