// study/summary.csv: rows appended whole as cases finish, cut back to whole rows on resume, and
// rewritten in case order through an atomic rename when the study completes.

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "lagrange/io.hpp"
#include "lagrange/sweep.hpp"

namespace lagrange::sweep {

namespace {

std::string join(const std::vector<std::string>& fields) {
  std::string line;
  for (size_t i = 0; i < fields.size(); ++i) line += (i ? "," : "") + fields[i];
  return line + "\n";
}

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw std::runtime_error(fmt::format("{}: {}: {}", path, what, std::strerror(errno)));
}

// The case number at the start of a row, or -1 when the row does not start with one.
long row_case(const std::string& line) {
  const auto comma = line.find(',');
  try {
    size_t used = 0;
    const long index = std::stol(line.substr(0, comma), &used);
    return used == comma && index >= 0 ? index : -1;
  } catch (const std::exception&) {
    return -1;
  }
}

}  // namespace

std::string csv_field(double value) {
  return std::isnan(value) ? "nan" : fmt::format("{:.17g}", value);
}

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string quoted = "\"";
  for (const char c : text) {
    if (c == '"') quoted += '"';
    quoted += c == '\n' || c == '\r' ? ' ' : c;
  }
  return quoted + "\"";
}

SummaryFile::SummaryFile(const std::string& path, std::vector<std::string> header, bool resume,
                         std::function<void()> before_first_write, bool repeats_replace)
    : path_(path), header_(std::move(header)), before_first_write_(std::move(before_first_write)) {
  const std::string head = join(header_);
  const bool exists = std::filesystem::exists(path_);
  if (exists && !resume)
    throw std::runtime_error(fmt::format(
        "{} exists: a study is already there; add --resume to finish it, or choose another "
        "directory",
        path_));
  if (exists) {
    // Keep the whole rows; a last row without its line end was being written when the
    // process died, and its case runs again.
    std::ifstream in(path_, std::ios::binary);
    std::stringstream buffer;
    buffer << in.rdbuf();
    const std::string text = buffer.str();
    if (text.compare(0, head.size(), head) != 0)
      throw std::runtime_error(
          fmt::format("{}: its columns are not those of this study (other parameters or metrics?); "
                      "--resume finishes the same study",
                      path_));
    size_t end = head.size();
    for (size_t at = head.size(); at < text.size();) {
      const auto nl = text.find('\n', at);
      if (nl == std::string::npos) break;
      // A row this study did not write (edited by hand, issue 37 item 2) is refused, not mixed in.
      const long index = row_case(text.substr(at, nl - at));
      if (index < 0 || (!done_.insert(static_cast<size_t>(index)).second && !repeats_replace))
        throw std::runtime_error(
            fmt::format("{}: row {} {}; --resume finishes a summary only as the study wrote it",
                        path_, done_.size() + 1,
                        index < 0 ? "does not start with a case number"
                                  : fmt::format("repeats case {}", index)));
      at = end = nl + 1;
    }
    if (end < text.size() && ::truncate(path_.c_str(), static_cast<off_t>(end)) != 0)
      fail(path_, "cannot cut off its unfinished last row");
    open_for_appending();
  }
}

// A new summary is published (its header, atomically) when the first row or finish() needs it:
// with worker processes, while the first cases run (docs/sweeps.md, "Speed").
void SummaryFile::open_for_appending() {
  if (before_first_write_) {
    before_first_write_();
    before_first_write_ = nullptr;
  }
  if (!std::filesystem::exists(path_)) write_file_atomically(path_, join(header_));
  fd_ = ::open(path_.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
  if (fd_ < 0) fail(path_, "cannot open for appending");
}

SummaryFile::~SummaryFile() {
  if (fd_ >= 0) ::close(fd_);
}

void SummaryFile::append(size_t index, const std::vector<std::string>& fields) {
  if (fd_ < 0) open_for_appending();
  const std::string line = join(fields);
  // One write of the whole row to an O_APPEND descriptor: a row is there whole or not at all
  // (a crash mid-write leaves a row without its line end, cut off on resume). A short write (the
  // disk filling up within the row) is continued, so that the error is the next write's own
  // errno, not a stale one (issue 37 item 16).
  for (size_t done = 0; done < line.size();) {
    const ssize_t n = ::write(fd_, line.data() + done, line.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n == 0) errno = ENOSPC;
    if (n <= 0) fail(path_, "cannot append a row");
    done += static_cast<size_t>(n);
  }
  done_.insert(index);
}

void SummaryFile::finish() {
  if (fd_ < 0) open_for_appending();
  std::ifstream in(path_, std::ios::binary);
  std::string line;
  std::getline(in, line);
  std::map<size_t, std::string> rows;
  while (std::getline(in, line))
    if (const long index = row_case(line); index >= 0) rows[static_cast<size_t>(index)] = line;
  std::string text = join(header_);
  for (const auto& [index, row] : rows) text += row + "\n";
  write_file_atomically(path_, text);
  ::close(fd_);
  fd_ = ::open(path_.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
  if (fd_ < 0) fail(path_, "cannot open for appending");
}

}  // namespace lagrange::sweep
