#include "cli/sweep_mpi.hpp"

#include <mpi.h>

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
  MPI_Init(nullptr, nullptr);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

MpiSession::~MpiSession() {
  MPI_Finalize();
}

void mpi_hand_out(const MpiSession& mpi, const std::vector<size_t>& pending,
                  const std::atomic<bool>* interrupt,
                  const std::function<void(size_t, const std::vector<std::string>&)>& record) {
  size_t next = 0;
  int working = mpi.size() - 1;
  while (working > 0) {
    MPI_Status status;
    MPI_Probe(MPI_ANY_SOURCE, kRow, MPI_COMM_WORLD, &status);
    int length = 0;
    MPI_Get_count(&status, MPI_CHAR, &length);
    std::string text(static_cast<size_t>(length), '\0');
    MPI_Recv(text.data(), length, MPI_CHAR, status.MPI_SOURCE, kRow, MPI_COMM_WORLD,
             MPI_STATUS_IGNORE);
    if (!text.empty()) {
      const std::vector<std::string> fields = unpack(text);
      record(std::stoul(fields.at(0)), fields);
    }
    const bool stop = next >= pending.size() || (interrupt && interrupt->load());
    const long long index = stop ? -1 : static_cast<long long>(pending[next++]);
    MPI_Send(&index, 1, MPI_LONG_LONG, status.MPI_SOURCE, kCase, MPI_COMM_WORLD);
    if (stop) --working;
  }
}

void mpi_work(const std::function<bool(size_t, std::vector<std::string>&)>& run) {
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
