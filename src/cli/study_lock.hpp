#pragma once
// STUDY/.lock (docs/sweeps.md, "Workers, progress and interruptions"): one study at a time in a
// directory. An exclusive flock on the file is held while the study runs; the kernel releases
// it when the process ends, however it ends.

#include <string>

namespace lagrange::cli {

/// The lock of the study directory `dir` (which must exist), held until destroyed; UsageError
/// naming the process that holds it when another study runs there.
class StudyLock {
 public:
  explicit StudyLock(const std::string& dir);
  ~StudyLock();
  StudyLock(const StudyLock&) = delete;
  StudyLock& operator=(const StudyLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace lagrange::cli
