#pragma once
// Machine code for tapes: their C (Tape::to_native_c) built by the system C compiler into a
// shared library, cached on disk under the hash of the source and the compiler (docs/theory.md §8).

#include <atomic>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "lagrange/tape.hpp"

namespace lagrange {

/// Where and with what MachineCode compiles.
struct MachineCodeOptions {
  std::string compiler;   ///< empty: $LAGRANGE_CC, else $CC, else `cc`, looked up on PATH
  std::string cache_dir;  ///< empty: $LAGRANGE_CACHE_DIR, else $XDG_CACHE_HOME/lagrange or
                          ///< ~/.cache/lagrange
  const std::atomic<bool>* cancel = nullptr;  ///< when set, a running compiler is stopped
};

/// Why machine code could not be had (no compiler, an unwritable cache, a compiler error);
/// callers fall back to the interpreter.
class MachineCodeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A loaded shared library with one function per tape; each computes exactly what Tape::eval
/// computes, bit for bit (the C keeps eval's operation order and is compiled without contraction).
class MachineCode {
 public:
  using Function = void (*)(const double* in, double* out, double* work);

  /// The library of `tapes`, from the cache or compiled into it. Throws MachineCodeError.
  static std::shared_ptr<const MachineCode> build(const std::vector<const Tape*>& tapes,
                                                  const MachineCodeOptions& options = {});
  /// The library of `tapes` if the cache has it already, else nullptr; never compiles. Throws
  /// MachineCodeError only for a cached file that cannot be loaded.
  static std::shared_ptr<const MachineCode> cached(const std::vector<const Tape*>& tapes,
                                                   const MachineCodeOptions& options = {});

  ~MachineCode();
  MachineCode(const MachineCode&) = delete;
  MachineCode& operator=(const MachineCode&) = delete;

  /// The function of tape i (in the order given to build).
  Function function(size_t i) const { return functions_.at(i); }
  bool from_cache() const { return from_cache_; }
  double seconds() const { return seconds_; }  ///< wall time of compiling (or loading)
  const std::string& path() const { return path_; }

 private:
  MachineCode() = default;
  /// dlopen + dlsym of `count` tape functions; nullptr when `path` does not exist.
  static std::shared_ptr<MachineCode> load(const std::string& path, size_t count);
  void* handle_ = nullptr;
  std::vector<Function> functions_;
  bool from_cache_ = false;
  double seconds_ = 0.0;
  std::string path_;
};

}  // namespace lagrange
