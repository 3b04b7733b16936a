#pragma once
// `mpirun -n K lagrange sweep …` (docs/sweeps.md, "MPI and clusters"): rank 0 hands out cases
// one at a time, runs cases itself and writes the summary; ranks 1 … K−1 run the cases it hands
// them (dynamic load balancing).
// Built only with MPI (LAGRANGE_HAVE_MPI, CMakeLists.txt).

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "lagrange/sweep.hpp"

namespace lagrange::cli {

/// MPI for the life of a study: MPI_Init_thread (MPI calls from the main thread only, other
/// threads running cases) on construction, MPI_Finalize on destruction.
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

/// Runs case `index` and fills its summary row `fields`; false when the case was interrupted
/// (no row then).
using RunCase = std::function<bool(size_t index, std::vector<std::string>& fields)>;
/// Records the row of a finished case.
using RecordRow = std::function<void(size_t index, const std::vector<std::string>& fields)>;

/// Rank 0: hands the `pending` cases out one at a time to ranks 1 … size−1, each a new case when
/// it returns a row, and runs cases itself with `run_here` on a second thread (MPI stays on the
/// calling thread, which polls for requests and sleeps between them); calls `record` for every
/// row, one call at a time. Stops handing out cases once `interrupt` is set. Returns when every
/// other rank has been told to stop and rank 0's own case has finished.
void mpi_hand_out(const MpiSession& mpi, const std::vector<size_t>& pending,
                  const std::atomic<bool>* interrupt, const RunCase& run_here,
                  const RecordRow& record);

/// Ranks 1 …: asks rank 0 for cases until told to stop, running each with `run`.
void mpi_work(const RunCase& run);

}  // namespace lagrange::cli
