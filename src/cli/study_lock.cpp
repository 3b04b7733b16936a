#include "cli/study_lock.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "cli/commands.hpp"

namespace lagrange::cli {

StudyLock::StudyLock(const std::string& dir) {
  const std::string path = dir + "/.lock";
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0)
    throw UsageError(fmt::format("-o {}: cannot create '{}': {}", dir, path, std::strerror(errno)));
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int err = errno;
    char holder[32] = {};
    const ssize_t n = ::pread(fd_, holder, sizeof holder - 1, 0);
    ::close(fd_);
    const std::string pid = n > 0 ? std::string(holder, static_cast<size_t>(n)) : "";
    if (err == EWOULDBLOCK)
      throw UsageError(fmt::format(
          "-o {}: another study is running in this directory ({}); wait for it to end, or "
          "choose another directory",
          dir, pid.empty() ? "another process" : "process " + pid.substr(0, pid.find('\n'))));
    throw UsageError(fmt::format("-o {}: cannot lock '{}': {}", dir, path, std::strerror(err)));
  }
  // Who holds it, for the message of a study refused while this one runs.
  const std::string pid = std::to_string(::getpid()) + "\n";
  if (::ftruncate(fd_, 0) != 0 ||
      ::pwrite(fd_, pid.data(), pid.size(), 0) != static_cast<ssize_t>(pid.size())) {
    const int err = errno;
    ::close(fd_);
    throw UsageError(fmt::format("-o {}: cannot write '{}': {}", dir, path, std::strerror(err)));
  }
}

StudyLock::~StudyLock() {
  ::close(fd_);  // releases the lock (forked workers, ended with this process, hold it no longer)
}

}  // namespace lagrange::cli
