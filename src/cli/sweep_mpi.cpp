#include "cli/sweep_mpi.hpp"

#include <mpi.h>

#include <chrono>
#include <exception>
#include <mutex>
#include <thread>

namespace lagrange::cli {

namespace {

constexpr int kRow = 1;   // worker → rank 0: a finished case's row ("" the first time)
constexpr int kCase = 2;  // rank 0 → worker: the next case number, or −1 to stop

// A row travels as its fields separated by '\x1f' (unit separator: never in a CSV field).
std::string pack(const std::vector<std::string>& fields) {
  std::string s;
  for (size_t i = 0; i < fields.size(); ++i) s += (i ? "\x1f" : "") + fields[i];
  return s;
}

std::vector<std::string> unpack(const std::string& s) {
  std::vector<std::string> fields;
  size_t start = 0;
  for (size_t at; (at = s.find('\x1f', start)) != std::string::npos; start = at + 1)
    fields.push_back(s.substr(start, at - start));
  fields.push_back(s.substr(start));
  return fields;
}

}  // namespace

MpiSession::MpiSession() {
  int provided = 0;
  MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

MpiSession::~MpiSession() {
  MPI_Finalize();
}

void mpi_hand_out(const MpiSession& mpi, const std::vector<size_t>& pending,
                  const std::atomic<bool>* interrupt, const RunCase& run_here,
                  const RecordRow& record) {
  std::mutex mutex;  // guards next, stopped, error and the calls of record
  size_t next = 0;
  bool stopped = false;
  std::exception_ptr error;
  const auto take = [&]() -> long long {
    const std::lock_guard<std::mutex> lock(mutex);
    if (stopped || next >= pending.size() || (interrupt && interrupt->load())) return -1;
    return static_cast<long long>(pending[next++]);
  };
  // Rank 0's own cases, taken from the same queue as the other ranks' (no MPI on this thread).
  std::thread here;
  if (run_here)
    here = std::thread([&] {
      try {
        for (long long index; (index = take()) >= 0;) {
          std::vector<std::string> fields;
          if (!run_here(static_cast<size_t>(index), fields)) return;
          const std::lock_guard<std::mutex> lock(mutex);
          record(static_cast<size_t>(index), fields);
        }
      } catch (...) {
        const std::lock_guard<std::mutex> lock(mutex);
        error = std::current_exception();
        stopped = true;
      }
    });
  const auto finish_here = [&] {
    {
      const std::lock_guard<std::mutex> lock(mutex);
      stopped = true;
    }
    if (here.joinable()) here.join();
  };
  try {
    int working = mpi.size() - 1;
    while (working > 0) {
      // A blocking probe would spin on the core rank 0's own cases run on: poll and sleep.
      int arrived = 0;
      MPI_Status status;
      MPI_Iprobe(MPI_ANY_SOURCE, kRow, MPI_COMM_WORLD, &arrived, &status);
      if (!arrived) {
        std::this_thread::sleep_for(std::chrono::microseconds(200));
        continue;
      }
      int length = 0;
      MPI_Get_count(&status, MPI_CHAR, &length);
      std::string text(static_cast<size_t>(length), '\0');
      MPI_Recv(text.data(), length, MPI_CHAR, status.MPI_SOURCE, kRow, MPI_COMM_WORLD,
               MPI_STATUS_IGNORE);
      if (!text.empty()) {
        const std::vector<std::string> fields = unpack(text);
        const std::lock_guard<std::mutex> lock(mutex);
        record(std::stoul(fields.at(0)), fields);
      }
      const long long index = take();
      MPI_Send(&index, 1, MPI_LONG_LONG, status.MPI_SOURCE, kCase, MPI_COMM_WORLD);
      if (index < 0) --working;
    }
  } catch (...) {
    finish_here();
    throw;
  }
  if (here.joinable()) here.join();
  if (error) std::rethrow_exception(error);
}

void mpi_work(const RunCase& run) {
  std::string row;
  for (;;) {
    MPI_Send(row.data(), static_cast<int>(row.size()), MPI_CHAR, 0, kRow, MPI_COMM_WORLD);
    long long index = -1;
    MPI_Recv(&index, 1, MPI_LONG_LONG, 0, kCase, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (index < 0) return;
    std::vector<std::string> fields;
    row = run(static_cast<size_t>(index), fields) ? pack(fields) : "";
  }
}

}  // namespace lagrange::cli
