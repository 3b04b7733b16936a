#pragma once
// Machine code for tapes: their C (Tape::to_native_c) built by the system C compiler into a
// shared library, cached on disk under the hash of the source and the compiler (docs/theory.md §8);
// an entry is loaded only from a private directory and when its recorded SHA-256 matches.

#include <atomic>
#include <functional>
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
  /// Polled every 10 ms by a compile on the caller's thread (never by a background one): true
  /// stops the compiler, MachineCodeError "compilation interrupted" (Ctrl-C).
  std::function<bool()> interrupted;
  /// Seconds the compiler may run before it is stopped (MachineCodeError); 0: $LAGRANGE_CC_TIMEOUT,
  /// else 300.
  double timeout = 0.0;
  /// When not empty (one offset per tape), tape i is compiled as Tape::to_shared_c reading its
  /// constants from work[constants_at[i] …]: the library serves every tape of its structure.
  std::vector<size_t> constants_at;
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

  /// The library of `tapes`, from the cache or compiled into it (replacing an entry that fails
  /// its SHA-256 check; note() says so). Throws MachineCodeError, also for a cache directory
  /// that others can write.
  static std::shared_ptr<const MachineCode> build(const std::vector<const Tape*>& tapes,
                                                  const MachineCodeOptions& options = {});
  /// The library of `tapes` if the cache has it already and it passes its SHA-256 check, else
  /// nullptr (with the reason in `*rejected` for an entry that failed the check); never
  /// compiles. Throws MachineCodeError for a file that cannot be loaded or an unsafe directory.
  static std::shared_ptr<const MachineCode> cached(const std::vector<const Tape*>& tapes,
                                                   const MachineCodeOptions& options = {},
                                                   std::string* rejected = nullptr);

  ~MachineCode();
  MachineCode(const MachineCode&) = delete;
  MachineCode& operator=(const MachineCode&) = delete;

  /// The function of tape i (in the order given to build).
  Function function(size_t i) const { return functions_.at(i); }
  bool from_cache() const { return from_cache_; }
  double seconds() const { return seconds_; }  ///< wall time of compiling (or loading)
  const std::string& path() const { return path_; }
  /// Why a cache entry was replaced by a fresh compile ("" when none was).
  const std::string& note() const { return note_; }

 private:
  MachineCode() = default;
  /// dlopen + dlsym of `count` tape functions from the verified bytes of `path`; nullptr when
  /// it does not exist or fails its record (built from `origin`), saying why in `*rejected`.
  static std::shared_ptr<MachineCode> load(const std::string& path, const std::string& origin,
                                           size_t count, std::string* rejected);
  void* handle_ = nullptr;
  int memfd_ = -1;  ///< the in-memory copy dlopen read, kept open while loaded
  std::string note_;
  std::vector<Function> functions_;
  bool from_cache_ = false;
  double seconds_ = 0.0;
  std::string path_;
};

}  // namespace lagrange
