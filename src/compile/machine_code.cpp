// MachineCode: tapes → C → shared library through the system C compiler, cached on disk
// (docs/theory.md §8, machine code). The library's name is the hash of everything that decides
// its contents — the C source, the compiler's path, size and modification time, and the flags —
// so a cached file is never stale, and two processes compiling the same tapes race harmlessly
// (each renames a finished file into place). Beside each library NAME.so, NAME.so.sha256 records
// the SHA-256 of its bytes and of what it was built from; an entry is loaded only from a private
// directory (not writable by group or others, ours) and only when both digests match, from a
// sealed in-memory copy of the verified bytes, so a truncated, foreign or swapped file is never
// run (issue 25 item 2): build() recompiles it, saying so.

#include "lagrange/machine_code.hpp"

#include <dlfcn.h>
#include <fcntl.h>
#include <fmt/format.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include "compile/c_compiler.hpp"
#include "compile/sha256.hpp"
#include "support/seconds_since.hpp"

namespace lagrange {

namespace {

// -ffp-contract=off keeps a·b + c from becoming a fused multiply-add, so that the library and
// Tape::eval agree bit for bit; -fno-math-errno lets sqrt compile to one instruction (same
// value). Changing the flags changes every cache key.
constexpr const char* kFlags[] = {"-std=c99",        "-O1", "-fPIC", "-shared", "-ffp-contract=off",
                                  "-fno-math-errno", "-w"};
constexpr const char* kFormat = "lagrange machine code 1";

using Clock = std::chrono::steady_clock;

std::string cache_directory(const MachineCodeOptions& options) {
  if (!options.cache_dir.empty()) return options.cache_dir;
  if (std::string d = environment_variable("LAGRANGE_CACHE_DIR"); !d.empty()) return d;
  if (std::string d = environment_variable("XDG_CACHE_HOME"); !d.empty()) return d + "/lagrange";
  if (std::string d = environment_variable("HOME"); !d.empty()) return d + "/.cache/lagrange";
  throw MachineCodeError("no cache directory: set LAGRANGE_CACHE_DIR (HOME is not set)");
}

/// 64-bit FNV-1a, folded over several strings.
struct Fnv {
  std::uint64_t h = 14695981039346656037ull;
  void add(const std::string& s) {
    for (unsigned char c : s) h = (h ^ c) * 1099511628211ull;
    h = (h ^ 0xff) * 1099511628211ull;  // separator, so ("ab","c") ≠ ("a","bc")
  }
};

std::string function_name(size_t i) {
  return fmt::format("lagrange_tape_{}", i);
}

/// The whole content of the open file `fd`; false on a read error.
bool read_all(int fd, std::string& out) {
  char buffer[65536];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n == 0) return true;
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return false;
    out.append(buffer, static_cast<size_t>(n));
  }
}

/// The bytes of the regular file at `path` (links not followed): Absent when it cannot be opened,
/// NotRegular for a FIFO, socket or device, which are never read (a FIFO's open() or read()
/// would block for ever; issue 37 item 11), Unreadable when a read fails.
enum class CacheRead { Read, Absent, NotRegular, Unreadable };
CacheRead read_regular(const std::string& path, std::string& bytes) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK);
  if (fd < 0) return CacheRead::Absent;
  struct stat st {};
  CacheRead result = CacheRead::NotRegular;
  if (::fstat(fd, &st) == 0 && S_ISREG(st.st_mode))
    result = read_all(fd, bytes) ? CacheRead::Read : CacheRead::Unreadable;
  ::close(fd);
  return result;
}

struct Plan {
  std::string source, compiler, dir, path;
  std::string origin;  ///< SHA-256 of everything the library is built from (the key's inputs)
  std::string record() const { return path + ".sha256"; }
};

Plan plan(const std::vector<const Tape*>& tapes, const MachineCodeOptions& options) {
  Plan p;
  p.source = "#include <math.h>\n";
  if (!options.constants_at.empty() && options.constants_at.size() != tapes.size())
    throw MachineCodeError(fmt::format("constants_at: expected {} offsets, got {}", tapes.size(),
                                       options.constants_at.size()));
  for (size_t i = 0; i < tapes.size(); ++i)
    p.source += options.constants_at.empty()
                    ? tapes[i]->to_native_c(function_name(i))
                    : tapes[i]->to_shared_c(function_name(i), options.constants_at[i]);
  p.compiler = resolve_c_compiler(options.compiler);
  p.dir = cache_directory(options);
  struct stat st {};
  if (::stat(p.compiler.c_str(), &st) != 0)
    throw MachineCodeError(
        fmt::format("cannot read the C compiler '{}': {}", p.compiler, std::strerror(errno)));
  std::vector<std::string> inputs{
      kFormat, p.source, p.compiler,
      fmt::format("{} {} {}", st.st_size, st.st_mtim.tv_sec, st.st_mtim.tv_nsec)};
  for (const char* f : kFlags) inputs.emplace_back(f);
  Fnv h;
  std::string joined;
  for (const std::string& s : inputs) {
    h.add(s);
    joined += std::to_string(s.size()) + ":" + s;
  }
  p.path = fmt::format("{}/tapes-{:016x}.so", p.dir, h.h);
  p.origin = sha256_hex(joined);
  return p;
}

/// Throws unless `dir`, when it exists, is ours and writable by no one else: code found in a
/// directory others can write could be anyone's.
void check_private(const std::string& dir) {
  struct stat st {};
  if (::lstat(dir.c_str(), &st) != 0) return;  // created 0700 when compiling
  if (!S_ISDIR(st.st_mode))
    throw MachineCodeError(fmt::format("the machine-code cache '{}' is not a directory", dir));
  if ((st.st_mode & (S_IWGRP | S_IWOTH)) != 0 || st.st_uid != ::geteuid())
    throw MachineCodeError(fmt::format(
        "the machine-code cache directory '{}' is {} (mode {:04o}): code in it is not loaded; "
        "make it private (chmod 700) or set LAGRANGE_CACHE_DIR to a private directory",
        dir, st.st_uid != ::geteuid() ? "owned by another user" : "writable by group or others",
        st.st_mode & 07777));
}

/// mkdir -p, owner-only for the directories it creates (the cache holds code that is loaded).
void make_directories(const std::string& dir) {
  for (size_t pos = 1; pos <= dir.size(); ++pos) {
    if (pos != dir.size() && dir[pos] != '/') continue;
    const std::string prefix = dir.substr(0, pos);
    if (::mkdir(prefix.c_str(), 0700) != 0 && errno != EEXIST)
      throw MachineCodeError(fmt::format("cannot create the machine-code cache directory '{}': {}",
                                         prefix, std::strerror(errno)));
  }
}

void write_file(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
  out.flush();
  if (!out) {
    const int err = errno;
    std::remove(path.c_str());
    throw MachineCodeError(
        fmt::format("cannot write '{}' into the machine-code cache: {}", path, std::strerror(err)));
  }
}

/// Runs the compiler with kFlags on `c_file` into `so_file`, its output going to `log_file`.
void run_compiler(const Plan& p, const std::string& c_file, const std::string& so_file,
                  const std::string& log_file, const MachineCodeOptions& options) {
  std::vector<std::string> args(std::begin(kFlags), std::end(kFlags));
  args.insert(args.end(), {"-o", so_file, c_file, "-lm"});
  run_c_compiler(p.compiler, args, log_file,
                 CompilerWatch{options.cancel, options.interrupted, options.timeout});
}

}  // namespace

MachineCode::~MachineCode() {
  if (handle_ != nullptr) ::dlclose(handle_);
  if (memfd_ >= 0) ::close(memfd_);
}

std::shared_ptr<MachineCode> MachineCode::load(const std::string& path, const std::string& origin,
                                               size_t count, std::string* rejected) {
  std::string bytes, record_text;
  const CacheRead library = read_regular(path, bytes);
  if (library == CacheRead::Absent) return nullptr;
  const CacheRead recorded = read_regular(path + ".sha256", record_text);
  if (library == CacheRead::NotRegular || recorded == CacheRead::NotRegular) {
    if (rejected != nullptr)
      *rejected = fmt::format("the cached '{}' or its '.sha256' is not a regular file", path);
    return nullptr;
  }
  // "<library digest>:<origin digest>", then a line end
  const std::string record = record_text.substr(0, record_text.find_first_of(" \t\r\n"));
  const bool read = library == CacheRead::Read;
  const std::string want = (read ? sha256_hex(bytes) : std::string("unreadable")) + ":" + origin;
  if (record != want) {
    if (rejected != nullptr)
      *rejected =
          fmt::format("the cached '{}' does not match its recorded SHA-256 ({})", path,
                      record.empty() ? "no record" : "truncated, replaced or another model's");
    return nullptr;
  }
  std::shared_ptr<MachineCode> code(new MachineCode());
  // dlopen a sealed in-memory copy of the verified bytes: the file may change after the check.
  code->memfd_ = ::memfd_create("lagrange-tapes", MFD_CLOEXEC | MFD_ALLOW_SEALING);
  std::string loaded = path;
  if (code->memfd_ >= 0) {
    size_t done = 0;
    while (done < bytes.size()) {
      const ssize_t n = ::write(code->memfd_, bytes.data() + done, bytes.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0)
        throw MachineCodeError(fmt::format("cannot copy '{}': {}", path, std::strerror(errno)));
      done += static_cast<size_t>(n);
    }
    ::fcntl(code->memfd_, F_ADD_SEALS, F_SEAL_SHRINK | F_SEAL_GROW | F_SEAL_WRITE | F_SEAL_SEAL);
    loaded = fmt::format("/proc/self/fd/{}", code->memfd_);
  }
  code->handle_ = ::dlopen(loaded.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (code->handle_ == nullptr) {
    const char* why = ::dlerror();
    throw MachineCodeError(
        fmt::format("cannot load '{}': {}", path, why != nullptr ? why : "unknown error"));
  }
  for (size_t i = 0; i < count; ++i) {
    void* f = ::dlsym(code->handle_, function_name(i).c_str());
    if (f == nullptr) throw MachineCodeError(fmt::format("'{}' lacks {}", path, function_name(i)));
    code->functions_.push_back(reinterpret_cast<Function>(f));
  }
  code->path_ = path;
  return code;
}

std::shared_ptr<const MachineCode> MachineCode::cached(const std::vector<const Tape*>& tapes,
                                                       const MachineCodeOptions& options,
                                                       std::string* rejected) {
  const auto start = Clock::now();
  const Plan p = plan(tapes, options);
  check_private(p.dir);
  auto code = load(p.path, p.origin, tapes.size(), rejected);
  if (code) {
    code->from_cache_ = true;
    code->seconds_ = seconds_since(start);
  }
  return code;
}

std::shared_ptr<const MachineCode> MachineCode::build(const std::vector<const Tape*>& tapes,
                                                      const MachineCodeOptions& options) {
  const auto start = Clock::now();
  const Plan p = plan(tapes, options);
  check_private(p.dir);
  std::string rejected;
  if (auto code = load(p.path, p.origin, tapes.size(), &rejected)) {
    code->from_cache_ = true;
    code->seconds_ = seconds_since(start);
    return code;
  }
  make_directories(p.dir);
  check_private(p.dir);
  // Private names for the files in flight; only the finished library is renamed into place.
  static std::atomic<unsigned> counter{0};
  const std::string stem =
      fmt::format("{}.{}.{}", p.path.substr(0, p.path.size() - 3), ::getpid(), counter++);
  const std::string c_file = stem + ".c", so_file = stem + ".so.part", log_file = stem + ".log",
                    record_file = stem + ".sha256.part";
  try {
    write_file(c_file, p.source);
    run_compiler(p, c_file, so_file, log_file, options);
    std::string bytes;
    const int fd = ::open(so_file.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0 || !read_all(fd, bytes))
      throw MachineCodeError(fmt::format("cannot read '{}': {}", so_file, std::strerror(errno)));
    ::close(fd);
    write_file(record_file, sha256_hex(bytes) + ":" + p.origin + "\n");
    // Library first, then its record: a reader between the two sees a mismatch and recompiles.
    if (std::rename(so_file.c_str(), p.path.c_str()) != 0 ||
        std::rename(record_file.c_str(), p.record().c_str()) != 0)
      throw MachineCodeError(
          fmt::format("cannot move '{}' into place: {}", so_file, std::strerror(errno)));
  } catch (...) {
    std::remove(c_file.c_str());
    std::remove(so_file.c_str());
    std::remove(log_file.c_str());
    std::remove(record_file.c_str());
    throw;
  }
  std::remove(c_file.c_str());
  std::remove(log_file.c_str());
  std::string again;
  auto code = load(p.path, p.origin, tapes.size(), &again);
  if (!code)
    throw MachineCodeError(again.empty() ? fmt::format("'{}' vanished from the cache", p.path)
                                         : again);
  if (!rejected.empty()) code->note_ = rejected + "; recompiled";
  code->seconds_ = seconds_since(start);
  return code;
}

}  // namespace lagrange
