// Output files published atomically (issue 25 item 1): each file is written to a unique
// temporary name beside it (NAME.<pid>.<random>.part), flushed to disk and renamed into place;
// a trajectory's sidecar is published after its CSV and records the CSV's size, and the old
// sidecar is removed before the new CSV appears, so no sidecar ever describes another file.

#include <dirent.h>
#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>
#include <stdexcept>
#include <vector>

#include "lagrange/io.hpp"

namespace lagrange {

namespace {

namespace fs = std::filesystem;

/// strerror(err) as the end of a sentence ("no space left on device").
std::string reason(int err) {
  std::string s = std::strerror(err);
  if (!s.empty()) s[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(s[0])));
  return s;
}

[[noreturn]] void cannot_write(const std::string& path, int err) {
  throw std::runtime_error("cannot write '" + path + "': " + reason(err));
}

/// The directory holding `path` ("." for a bare file name).
std::string directory_of(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  return parent.empty() ? "." : parent.string();
}

/// What a file system entry of type `mode` is, for a message ("a directory", "a FIFO", …).
const char* entry_kind(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

/// Throws unless `path` is absent or a regular file (links followed): the rename that publishes a
/// file would replace a device node, a FIFO or a socket by a regular file (issue 37 item 1).
void require_regular_or_absent(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0 || S_ISREG(st.st_mode)) return;
  throw std::runtime_error("cannot write '" + path + "': it exists and is " +
                           entry_kind(st.st_mode) + ", not a regular file");
}

/// Removes NAME.<pid>.<suffix>.part left beside `path` by processes that no longer run (a
/// writer killed with SIGKILL cannot remove its own), and the NAME.part of earlier versions.
void remove_stale_parts(const std::string& path) {
  ::unlink((path + ".part").c_str());
  const std::string name = fs::path(path).filename().string() + ".";
  DIR* dir = opendir(directory_of(path).c_str());
  if (!dir) return;
  while (const dirent* e = readdir(dir)) {
    const std::string entry = e->d_name;
    if (entry.size() <= name.size() + 5 || entry.compare(0, name.size(), name) != 0 ||
        entry.compare(entry.size() - 5, 5, ".part") != 0)
      continue;
    const std::string middle = entry.substr(name.size(), entry.size() - name.size() - 5);
    const long pid = std::strtol(middle.c_str(), nullptr, 10);
    if (pid > 0 && kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH)
      ::unlink((directory_of(path) + "/" + entry).c_str());
  }
  closedir(dir);
}

/// SIGINT held back while temporary files exist: the CLI's handler ends a process that is not
/// keeping its work with _exit(130), which would leave them behind; held, it arrives once they
/// are published or removed.
class HoldSigint {
 public:
  HoldSigint() {
    sigset_t hold;
    sigemptyset(&hold);
    sigaddset(&hold, SIGINT);
    pthread_sigmask(SIG_BLOCK, &hold, &previous_);
  }
  HoldSigint(const HoldSigint&) = delete;
  HoldSigint& operator=(const HoldSigint&) = delete;
  ~HoldSigint() { pthread_sigmask(SIG_SETMASK, &previous_, nullptr); }

 private:
  sigset_t previous_{};
};

/// A file written under a unique temporary name beside its final `path`; publish() renames it
/// into place, and a StagedFile destroyed unpublished removes its temporary file.
class StagedFile {
 public:
  StagedFile(const std::string& path, const std::string& text) : path_(path) {
    std::random_device random;
    tmp_ = path + "." + std::to_string(getpid()) + "." + std::to_string(random()) + ".part";
    const int fd = ::open(tmp_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0) cannot_write(path, errno);
    created_ = true;
    for (size_t done = 0; done < text.size();) {
      const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) close_and_fail(fd, errno);
      done += static_cast<size_t>(n);
    }
    if (::fsync(fd) != 0) close_and_fail(fd, errno);
    if (::close(fd) != 0) {
      const int err = errno;
      ::unlink(tmp_.c_str());
      cannot_write(path_, err);
    }
  }
  StagedFile(const StagedFile&) = delete;
  StagedFile& operator=(const StagedFile&) = delete;
  ~StagedFile() {
    if (created_) ::unlink(tmp_.c_str());
  }

  void publish() {
    if (std::rename(tmp_.c_str(), path_.c_str()) != 0)
      throw std::runtime_error("cannot rename '" + tmp_ + "' to '" + path_ + "': " + reason(errno));
    created_ = false;
  }

 private:
  // The constructor throws: the destructor will not run, so the temporary goes here.
  [[noreturn]] void close_and_fail(int fd, int err) {
    ::close(fd);
    ::unlink(tmp_.c_str());
    cannot_write(path_, err);
  }

  std::string path_, tmp_;
  bool created_ = false;
};

/// An exclusive lock on a directory (flock), so that concurrent writers publish one at a time.
class DirectoryLock {
 public:
  explicit DirectoryLock(const std::string& dir)
      : fd_(::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC)) {
    if (fd_ >= 0)
      while (::flock(fd_, LOCK_EX) != 0 && errno == EINTR) {
      }
  }
  DirectoryLock(const DirectoryLock&) = delete;
  DirectoryLock& operator=(const DirectoryLock&) = delete;
  /// Makes the renames durable, then releases the lock.
  ~DirectoryLock() {
    if (fd_ < 0) return;
    ::fsync(fd_);
    ::close(fd_);
  }

 private:
  int fd_;
};

}  // namespace

void create_parent_directories(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  if (parent.empty()) return;
  std::error_code ec;
  fs::create_directories(parent, ec);
  if (ec)
    throw std::runtime_error("cannot create the directory '" + parent.string() + "' for '" + path +
                             "': " + ec.message());
}

void check_writable(const std::string& path) {
  require_regular_or_absent(path);
  // The directories the probe needs are made for it and removed after it, deepest first: a run
  // that fails later leaves none behind (issue 37 item 19); the write makes them again.
  std::vector<fs::path> made;
  std::error_code ec;
  for (fs::path dir = fs::path(path).parent_path(); !dir.empty() && !fs::exists(dir, ec);
       dir = dir.parent_path())
    made.push_back(dir);
  const auto remove_made = [&made] {
    std::error_code ignored;
    for (const fs::path& dir : made) fs::remove(dir, ignored);  // only while empty
  };
  try {
    create_parent_directories(path);
    const HoldSigint hold;
    StagedFile probe(path, "");  // removed unpublished: the location takes a new file
  } catch (...) {
    remove_made();
    throw;
  }
  remove_made();
}

void write_file_atomically(const std::string& path, const std::string& text) {
  require_regular_or_absent(path);
  create_parent_directories(path);
  remove_stale_parts(path);
  const HoldSigint hold;
  StagedFile file(path, text);
  DirectoryLock lock(directory_of(path));
  file.publish();
}

void write_file_with_sidecar(const std::string& path, const std::string& text,
                             const std::string& sidecar_text) {
  const std::string sidecar = path + ".json";
  require_regular_or_absent(path);
  require_regular_or_absent(sidecar);
  create_parent_directories(path);
  remove_stale_parts(path);
  remove_stale_parts(sidecar);
  const HoldSigint hold;
  StagedFile file(path, text), side(sidecar, sidecar_text);
  DirectoryLock lock(directory_of(path));
  // Old sidecar gone before the new file appears: a kill between the steps leaves a file
  // without a sidecar (not a full run, docs/errors.md), never a sidecar describing another.
  if (::unlink(sidecar.c_str()) != 0 && errno != ENOENT)
    throw std::runtime_error("cannot replace '" + sidecar + "': " + reason(errno));
  file.publish();
  side.publish();
}

}  // namespace lagrange
