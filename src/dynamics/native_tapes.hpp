#pragma once
// The machine code behind a set of tapes (docs/theory.md §8): a Dynamics' three specialised tapes,
// or the optimiser's second derivatives; their library compiled at once or by a background
// thread, and published to the evaluating thread through one atomic flag.

#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "lagrange/dynamics.hpp"
#include "lagrange/machine_code.hpp"

namespace lagrange::dynamics {

/// Tape order in a Dynamics' library.
enum TapeSlot : size_t { kDynamicsTape = 0, kObservablesTape = 1, kInputsTape = 2 };

struct NativeTapes {
  Evaluation mode = Evaluation::Interpreter;
  MachineCodeOptions options;  ///< as given; `cancel` is replaced by ours
  /// Background: a first tape shorter than this interprets faster than it compiles, and is not
  /// compiled (a cached library is still used).
  size_t min_instructions = Dynamics::kBackgroundMinInstructions;

  /// The function of tape `slot` when machine code is ready, else nullptr (the interpreter runs).
  MachineCode::Function function(size_t slot) const {
    return ready.load(std::memory_order_acquire) ? functions[slot] : nullptr;
  }

  /// Stop and join a background compiler run; forget the current library.
  void reset();
  /// Machine code for `tapes` per `mode` (joins any earlier run first).
  void start(const std::vector<const Tape*>& tapes);
  /// SharedMachineCode: the library of `tapes`' structure, their constants at `offsets` in the
  /// evaluating Dynamics' work array; nothing to do when it is the structure of the library
  /// already loaded (or of the one that failed: no compiler run per parameter value).
  void start_shared(const std::vector<const Tape*>& tapes, const std::vector<size_t>& offsets);
  std::string note() const;
  std::string error() const;

  ~NativeTapes() { reset(); }

 private:
  void publish(std::shared_ptr<const MachineCode> library);
  void fail(const std::string& why);
  void skip(const std::string& why);

  std::atomic<bool> ready{false};
  std::atomic<bool> cancel{false};
  std::vector<MachineCode::Function> functions;  ///< one per tape, set before `ready`
  std::shared_ptr<const MachineCode> library;
  std::thread worker;
  mutable std::mutex mutex;  // guards `why` and `library` between the worker and note()
  std::string why;           // why machine code failed
  std::string skipped;       // why machine code was not tried
  std::string cache_note;    // why a cache entry was not loaded
  std::string shared_key;    // SharedMachineCode: the C of the structure last built (or tried)
};

}  // namespace lagrange::dynamics
