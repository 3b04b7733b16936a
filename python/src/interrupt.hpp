#pragma once
// Ctrl-C during a run started from Python (docs/python.md, "Interrupting a run"). Python's own
// SIGINT handler only marks the signal for the interpreter, which does not look while the engine
// runs with the GIL released; so around a run on the main thread a handler of ours sets the flag
// the engine polls (SimulationOptions::interrupt, PoolOptions::interrupt,
// OptimizeOptions::interrupt), and the signal is handed back to Python when the run returns.

#include <pybind11/pybind11.h>

#include <atomic>
#include <csignal>
#include <initializer_list>
#include <utility>

namespace lagrange::python {

/// Construct with the GIL held, before releasing it for the run. On the main thread, while
/// Python handles SIGINT with a function of its own (signal.default_int_handler unless the
/// program set another), SIGINT sets flag() instead; elsewhere (another thread, SIGINT ignored
/// or left to the system) flag() is never set and nothing changes.
class InterruptibleRun {
 public:
  InterruptibleRun();
  ~InterruptibleRun();
  InterruptibleRun(const InterruptibleRun&) = delete;
  InterruptibleRun& operator=(const InterruptibleRun&) = delete;

  /// What the engine polls; nullptr when this run cannot be interrupted this way.
  const std::atomic<bool>* flag() const;

  /// With the GIL held, after the run: restores Python's handler and, when SIGINT came, runs
  /// it as though the signal arrived now. Returns true when it raised (KeyboardInterrupt, the
  /// error set in Python), false when nothing came or the handler returned normally.
  bool raised();

  /// Sets the attributes on the error raised() set (the partial results), then throws it.
  [[noreturn]] static void throw_with(
      std::initializer_list<std::pair<const char*, pybind11::handle>> attributes);

 private:
  void restore();
  bool installed_ = false;
  struct sigaction previous_ {};
};

}  // namespace lagrange::python
