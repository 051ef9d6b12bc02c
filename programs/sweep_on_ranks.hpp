#pragma once
// `growshell sweep` under an MPI launcher (mpirun -n K growshell sweep ...): every rank runs
// whole points of the sweep, taken one at a time from a shared counter, and rank 0 gathers
// their results into DIR/sweep.json and sweep.csv. Only the driver uses MPI; the library's
// sweep (studies/parameter_sweep.hpp) knows nothing of it.

#include <functional>
#include <string>
#include <vector>

#include "libshell/io/scene.hpp"
#include "studies/parameter_sweep.hpp"
#include "studies/scene_study.hpp"

namespace growshell {

/// Whether an MPI launcher started this process (OpenMPI's, MPICH's or a PMIx launcher's
/// environment). A plain `growshell sweep` never initialises MPI.
bool launched_by_mpi_launcher();

/// The sweep over all ranks of MPI_COMM_WORLD. Rank 0 checks the input and prepares DIR
/// (open_sweep_directory) before any rank runs a point; a refusal is reported by rank 0 and
/// makes every rank return 2. Each rank then runs points in the order it draws them
/// (run_sweep_point; its log lines behind "[rank R]"), and rank 0 writes the summaries, at the
/// start (every point pending) and at the end. Initialises and finalises MPI.
struct RankedSweepOutcome {
  /// 0 when every point completed, 3 when some did not (rank 0; the others return 0), 2 for
  /// refused input.
  int exit_code = 2;
  /// This process is rank 0 and wrote the final summaries (so it may draw the figure).
  bool wrote_summary = false;
};
RankedSweepOutcome run_sweep_on_ranks(const Scene& base, const std::vector<SweepParameter>& parameters,
                       const std::string& dir, ExistingOutput existing,
                       const std::function<void(const std::string&)>& say);

}  // namespace growshell
