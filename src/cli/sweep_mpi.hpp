#pragma once
// `mpirun -n K lagrange sweep …` (docs/sweeps.md, "MPI and clusters"): rank 0 hands out cases
// one at a time and writes the summary; ranks 1 … K−1 run them (dynamic load balancing).
// Built only with MPI (LAGRANGE_HAVE_MPI, CMakeLists.txt).

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "lagrange/sweep.hpp"

namespace lagrange::cli {

/// MPI for the life of a study: MPI_Init on construction, MPI_Finalize on destruction.
class MpiSession {
 public:
  MpiSession();
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }

 private:
  int rank_ = 0, size_ = 1;
};

/// Rank 0: hands the `pending` cases out to ranks 1 … size−1, each a new case when it returns
/// a row, and calls `record(index, fields)` for each row returned; stops handing out cases once
/// `interrupt` is set. Returns when every other rank has been told to stop.
void mpi_hand_out(const MpiSession& mpi, const std::vector<size_t>& pending,
                  const std::atomic<bool>* interrupt,
                  const std::function<void(size_t, const std::vector<std::string>&)>& record);

/// Ranks 1 …: asks rank 0 for cases until told to stop; `run(index, fields)` runs a case and
/// fills its row, returning false when the case was interrupted (no row is sent then).
void mpi_work(const std::function<bool(size_t, std::vector<std::string>&)>& run);

}  // namespace lagrange::cli
