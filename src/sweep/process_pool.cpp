// The workers of a study as processes forked from this one (docs/sweeps.md, "Speed"): each is
// single-threaded, so it allocates without the locks glibc takes once a process has a second
// thread, and runs a case as a lone `simulate` does. They take the next case from a counter in
// shared memory and send each result down their own pipe; this process calls `done`.

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <exception>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>

#include "lagrange/dynamics.hpp"
#include "lagrange/sweep.hpp"
#include "sweep/worker_workspace.hpp"

namespace lagrange::sweep {

namespace {

// What the workers share: the next case to take, and whether to stop taking them.
struct Shared {
  std::atomic<size_t> next{0};
  std::atomic<bool> stop{false};
};
static_assert(std::atomic<size_t>::is_always_lock_free && std::atomic<bool>::is_always_lock_free,
              "the counter must work across processes");

// A message from a worker: the case it starts, a case's result, or the error that stopped it.
enum class Kind : std::uint32_t { Started, Result, Error };

struct Header {
  Kind kind;
  std::uint32_t status;
  std::uint64_t index, metrics, text;  // counts of doubles and of bytes that follow
  double failure_time, wall_seconds, read_seconds;
};

void append_bytes(std::string& out, const void* data, size_t size) {
  out.append(static_cast<const char*>(data), size);
}

std::string message(Kind kind, const CaseResult& r, const std::string& text) {
  const Header h{kind,           static_cast<std::uint32_t>(r.status),
                 r.index,        r.metrics.size(),
                 text.size(),    r.failure_time,
                 r.wall_seconds, r.read_seconds};
  std::string out;
  append_bytes(out, &h, sizeof h);
  if (!r.metrics.empty()) append_bytes(out, r.metrics.data(), r.metrics.size() * sizeof(double));
  out += text;
  return out;
}

// The whole of `data` down `fd` (a pipe: a long message may take several writes).
bool send(int fd, const std::string& data) {
  size_t sent = 0;
  while (sent < data.size()) {
    const ssize_t n = ::write(fd, data.data() + sent, data.size() - sent);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    sent += static_cast<size_t>(n);
  }
  return true;
}

// Case `index` on `dyn`, as every worker runs it (this process's own cases included).
CaseResult run_slot(Dynamics& dyn, size_t index, const std::vector<CaseInput>& inputs,
                    const std::vector<Metric>& metrics, const PoolOptions& options,
                    Trajectory& traj) {
  CaseRead read = options.read ? options.read(index) : CaseRead{inputs[index], {}, -1.0};
  if (read.input) read.input->options.interrupt = options.interrupt;
  CaseResult result = run_case(dyn, read, metrics, options.keep ? &traj : nullptr);
  result.index = index;
  result.read_seconds = read.read_seconds;
  if (result.status != Trajectory::Status::Interrupted && options.keep && read.input)
    options.keep(index, traj);
  return result;
}

// A worker process: cases until none is left, the study stops or it is interrupted; never
// returns.
[[noreturn]] void work(const std::shared_ptr<const CompiledModel>& model,
                       const std::vector<CaseInput>& inputs, const std::vector<size_t>& pending,
                       const std::vector<Metric>& metrics, const PoolOptions& options,
                       Shared& shared, int fd) {
  int code = 0;
  try {
    std::optional<Dynamics> own;
    Dynamics& dyn = options.workspace ? *options.workspace : worker_workspace(model, options, own);
    Trajectory traj;
    const auto stopped = [&] {
      return shared.stop.load() || (options.interrupt && options.interrupt->load());
    };
    for (size_t slot = shared.next++; slot < pending.size() && !stopped(); slot = shared.next++) {
      CaseResult started;  // so that a death in this case names it (issue 37 item 20)
      started.index = pending[slot];
      if (!send(fd, message(Kind::Started, started, ""))) {
        code = 1;
        break;
      }
      const CaseResult result = run_slot(dyn, pending[slot], inputs, metrics, options, traj);
      if (result.status == Trajectory::Status::Interrupted) break;
      if (!send(fd, message(Kind::Result, result, result.reason))) {
        code = 1;
        break;
      }
    }
  } catch (const std::exception& e) {
    send(fd, message(Kind::Error, {}, e.what()));
    code = 1;
  } catch (...) {
    send(fd, message(Kind::Error, {}, "an unknown exception"));
    code = 1;
  }
  ::close(fd);
  _exit(code);  // no atexit handlers or static destructors: they are the parent's to run
}

// This process has no thread besides the calling one (fork copies only the caller, and any lock
// another thread held would stay held in the worker).
bool single_threaded() {
  std::error_code ec;
  size_t threads = 0;
  for (auto it = std::filesystem::directory_iterator("/proc/self/task", ec);
       !ec && it != std::filesystem::directory_iterator(); it.increment(ec))
    ++threads;
  return !ec && threads == 1;
}

// The messages received from one worker.
struct Worker {
  pid_t pid = -1;
  int fd = -1;
  std::string buffer;
  std::optional<size_t> running;  // the case it said it started and has not sent
};

// The whole messages at the front of `w.buffer`, handed to `result` or `error` and removed.
template <class OnResult, class OnError>
void take_messages(Worker& w, OnResult result, OnError error) {
  size_t at = 0;
  while (w.buffer.size() - at >= sizeof(Header)) {
    Header h;
    std::memcpy(&h, w.buffer.data() + at, sizeof h);
    const size_t size = sizeof h + h.metrics * sizeof(double) + h.text;
    if (w.buffer.size() - at < size) break;
    const char* body = w.buffer.data() + at + sizeof h;
    const std::string text(body + h.metrics * sizeof(double), h.text);
    if (h.kind == Kind::Error) {
      error(text);
    } else if (h.kind == Kind::Started) {
      w.running = h.index;
    } else {
      w.running.reset();
      CaseResult r;
      r.index = h.index;
      r.status = static_cast<Trajectory::Status>(h.status);
      r.reason = text;
      r.failure_time = h.failure_time;
      r.wall_seconds = h.wall_seconds;
      r.read_seconds = h.read_seconds;
      r.metrics.resize(h.metrics);
      if (h.metrics > 0)  // a failed case has none, and memcpy must not see a null pointer
        std::memcpy(r.metrics.data(), body, h.metrics * sizeof(double));
      result(r);
    }
    at += size;
  }
  w.buffer.erase(0, at);
}

// Waits for worker `w` to end; `stop` is told why when it died (WorkerDied) or stopped with an
// error.
template <class Stop>
void reap(const Worker& w, Stop stop) {
  int status = 0;
  while (::waitpid(w.pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFSIGNALED(status) && WTERMSIG(status) != SIGINT) {
    const int sig = WTERMSIG(status);
    std::string why = std::string("a worker process (pid ") + std::to_string(w.pid) +
                      ") died from signal " + std::to_string(sig) + " (" + strsignal(sig) + ")";
    why += w.running ? " while running case " + std::to_string(*w.running) : " between cases";
    stop(std::make_exception_ptr(WorkerDied(why, w.running, sig)));
  } else if (WIFEXITED(status) && WEXITSTATUS(status) != 0) {
    stop(std::make_exception_ptr(std::runtime_error("a worker process stopped with an error")));
  }
}

}  // namespace

void run_pool_processes(const std::shared_ptr<const CompiledModel>& model,
                        const std::vector<CaseInput>& inputs, const std::vector<size_t>& pending,
                        const std::vector<Metric>& metrics, const PoolOptions& options) {
  const size_t n = std::min(options.workers, pending.size());
  if (n < 2 || !single_threaded()) return run_pool(model, inputs, pending, metrics, options);
  void* memory =
      mmap(nullptr, sizeof(Shared), PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
  if (memory == MAP_FAILED) return run_pool(model, inputs, pending, metrics, options);
  Shared* shared = new (memory) Shared;
  std::vector<Worker> workers;
  std::exception_ptr error;  // the first: a worker's exception, a worker's death, or `done`'s
  // n − 1 worker processes; this one is the n-th, taking their results between its cases.
  const pid_t parent = ::getpid();
  const auto failure = [](const std::string& why) {
    return std::make_exception_ptr(std::runtime_error(why));
  };
  for (size_t i = 1; i < n && !error; ++i) {
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0) {
      error = failure(std::string("cannot make a pipe for a worker: ") + std::strerror(errno));
      break;
    }
    const pid_t pid = ::fork();
    if (pid == 0) {
      // A worker ends with this process, even one killed by SIGKILL, instead of running its
      // case on as a child of init (issue 37 item 9); getppid() catches a death before prctl.
      if (::prctl(PR_SET_PDEATHSIG, SIGKILL) != 0 || ::getppid() != parent) _exit(1);
      ::close(fds[0]);
      for (const Worker& w : workers) ::close(w.fd);
      work(model, inputs, pending, metrics, options, *shared, fds[1]);
    }
    ::close(fds[1]);
    if (pid < 0) {
      ::close(fds[0]);
      error = failure(std::string("cannot start a worker process: ") + std::strerror(errno));
      break;
    }
    workers.push_back({pid, fds[0], {}, {}});
  }
  if (error) shared->stop = true;
  bool forwarded = false;  // this process's interrupt, passed on to the workers
  const auto stop_for = [&](std::exception_ptr why) {
    if (!error) error = std::move(why);
    shared->stop = true;
  };
  const auto stop_with = [&](const std::string& why) { stop_for(failure(why)); };
  const auto on_result = [&](const CaseResult& r) {
    if (!options.done || shared->stop) return;
    try {
      options.done(r);
    } catch (const std::exception& e) {
      stop_with(e.what());
    }
  };
  size_t open = workers.size();
  // The workers' messages that have arrived, waiting up to `timeout` ms for the first.
  const auto take_results = [&](int timeout) {
    if (options.interrupt && options.interrupt->load() && !forwarded) {
      for (const Worker& w : workers) ::kill(w.pid, SIGINT);
      forwarded = true;
    }
    std::vector<pollfd> fds;
    std::vector<Worker*> polled;
    for (Worker& w : workers)
      if (w.fd >= 0) {
        fds.push_back({w.fd, POLLIN, 0});
        polled.push_back(&w);
      }
    if (::poll(fds.data(), fds.size(), timeout) < 0 && errno != EINTR)
      stop_with(std::string("cannot wait for the workers: ") + std::strerror(errno));
    for (size_t i = 0; i < fds.size(); ++i) {
      if (fds[i].revents == 0) continue;
      Worker& w = *polled[i];
      char chunk[65536];
      const ssize_t got = ::read(w.fd, chunk, sizeof chunk);
      if (got < 0 && errno == EINTR) continue;
      if (got > 0) {
        w.buffer.append(chunk, static_cast<size_t>(got));
        take_messages(w, on_result, stop_with);
        continue;
      }
      // The worker's end is closed: it has ended (or is ending); one that died stops the others
      // after their case.
      ::close(w.fd);
      w.fd = -1;
      --open;
      reap(w, stop_for);
    }
  };
  // This process's own cases (its workspace and caches are warm, and it is not a third process
  // competing with n workers for n cores), the workers' results taken before each.
  const auto stopped = [&] {
    return shared->stop.load() || (options.interrupt && options.interrupt->load());
  };
  if (!error) {
    try {
      std::optional<Dynamics> own;
      Dynamics& dyn =
          options.workspace ? *options.workspace : worker_workspace(model, options, own);
      Trajectory traj;
      for (size_t slot = shared->next++; slot < pending.size() && !stopped();
           slot = shared->next++) {
        take_results(0);
        if (stopped()) break;
        const CaseResult result = run_slot(dyn, pending[slot], inputs, metrics, options, traj);
        if (result.status == Trajectory::Status::Interrupted) break;
        on_result(result);
      }
    } catch (const std::exception& e) {
      stop_with(e.what());
    }
  }
  while (open > 0) take_results(100);
  shared->~Shared();
  munmap(memory, sizeof(Shared));
  if (error) std::rethrow_exception(error);
}

}  // namespace lagrange::sweep
