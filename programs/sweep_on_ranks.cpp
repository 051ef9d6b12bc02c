#include "sweep_on_ranks.hpp"

#include <mpi.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

namespace growshell {
namespace {

int world_rank() {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  return rank;
}

/// Broadcasts rank 0's text to every rank.
std::string broadcast_text(std::string text) {
  long long size = static_cast<long long>(text.size());
  MPI_Bcast(&size, 1, MPI_LONG_LONG, 0, MPI_COMM_WORLD);
  text.resize(static_cast<std::size_t>(size));
  MPI_Bcast(text.data(), static_cast<int>(size), MPI_CHAR, 0, MPI_COMM_WORLD);
  return text;
}

/// A counter on rank 0 that every rank draws the next point index from (one-sided, so rank 0
/// need not stop its own point to serve the others).
class SharedCounter {
 public:
  SharedCounter() {
    const MPI_Aint size = world_rank() == 0 ? sizeof(long long) : 0;
    MPI_Win_allocate(size, sizeof(long long), MPI_INFO_NULL, MPI_COMM_WORLD, &value_, &window_);
    if (world_rank() == 0) {
      MPI_Win_lock(MPI_LOCK_EXCLUSIVE, 0, 0, window_);
      *value_ = 0;
      MPI_Win_unlock(0, window_);
    }
    MPI_Barrier(MPI_COMM_WORLD);
  }
  SharedCounter(const SharedCounter&) = delete;
  SharedCounter& operator=(const SharedCounter&) = delete;
  ~SharedCounter() { MPI_Win_free(&window_); }

  /// The counter's value before adding 1 to it, atomically across ranks.
  long long next() {
    const long long one = 1;
    long long drawn = 0;
    MPI_Win_lock(MPI_LOCK_SHARED, 0, 0, window_);
    MPI_Fetch_and_op(&one, &drawn, MPI_LONG_LONG, 0, 0, MPI_SUM, window_);
    MPI_Win_unlock(0, window_);
    return drawn;
  }

 private:
  long long* value_ = nullptr;
  MPI_Win window_ = MPI_WIN_NULL;
};

// One point's result as text: "index status reason_size reason results_size results".
void encode(std::ostringstream& out, int index, const SweepPointResult& r) {
  out << index << ' ' << static_cast<int>(r.status) << ' ' << r.reason.size() << ' ' << r.reason
      << ' ' << r.results_json.size() << ' ' << r.results_json << ' ';
}

std::string read_sized(std::istringstream& in) {
  std::size_t size = 0;
  in >> size;
  in.get();  // the separating space
  std::string text(size, '\0');
  in.read(text.data(), static_cast<std::streamsize>(size));
  return text;
}

void decode(const std::string& text, std::vector<std::optional<SweepPointResult>>& known) {
  std::istringstream in(text);
  int index = 0, status = 0;
  while (in >> index >> status) {
    SweepPointResult r;
    r.status = static_cast<SweepPointResult::Status>(status);
    r.reason = read_sized(in);
    r.results_json = read_sized(in);
    if (index < 0 || static_cast<std::size_t>(index) >= known.size())
      throw std::runtime_error("a rank returned the unknown sweep point " + std::to_string(index));
    known[static_cast<std::size_t>(index)] = r;
  }
}

/// Every rank's encoded results, concatenated on rank 0 (empty elsewhere).
std::string gather_text(const std::string& mine) {
  int size = 0, ranks = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  const int length = static_cast<int>(mine.size());
  std::vector<int> lengths(static_cast<std::size_t>(ranks)), offsets(static_cast<std::size_t>(ranks));
  MPI_Gather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  for (int r = 0; r < ranks; ++r) {
    offsets[static_cast<std::size_t>(r)] = size;
    size += lengths[static_cast<std::size_t>(r)];
  }
  std::string all(world_rank() == 0 ? static_cast<std::size_t>(size) : 0, '\0');
  MPI_Gatherv(mine.data(), length, MPI_CHAR, all.data(), lengths.data(), offsets.data(), MPI_CHAR,
              0, MPI_COMM_WORLD);
  return all;
}

RankedSweepOutcome sweep(const Scene& base, const std::vector<SweepParameter>& parameters, const std::string& dir,
          ExistingOutput existing, const std::function<void(const std::string&)>& say) {
  const int rank = world_rank();
  int ranks = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  const std::vector<SweepPoint> points = sweep_points(parameters);
  // Rank 0 alone touches DIR before the points run; a refusal stops every rank.
  std::string refusal;
  if (rank == 0) {
    try {
      open_sweep_directory(dir, base, parameters, existing);
      write_sweep_summary(dir, parameters, points,
                          std::vector<std::optional<SweepPointResult>>(points.size()));
    } catch (const std::exception& e) {
      refusal = e.what();
      if (refusal.empty()) refusal = "the sweep directory could not be prepared";
    }
  }
  refusal = broadcast_text(refusal);
  if (!refusal.empty()) {
    if (rank == 0) std::fprintf(stderr, "growshell: error: %s\n", refusal.c_str());
    return {2, false};
  }
  if (rank == 0)
    say("# growshell sweep: study " + study_kind_name(base.study.kind) + ", " +
        std::to_string(points.size()) + " points on " + std::to_string(ranks) +
        " MPI ranks, output " + dir);
  const std::string tag = "[rank " + std::to_string(rank) + "] ";
  const auto say_ranked = [&](const std::string& line) { say(tag + line); };
  std::ostringstream mine;
  SharedCounter counter;
  for (long long i = counter.next(); i < static_cast<long long>(points.size()); i = counter.next()) {
    const SweepPoint& point = points[static_cast<std::size_t>(i)];
    say_ranked("# point " + point.directory);
    const SweepPointResult r = run_sweep_point(sweep_point_scene(base, point, dir), say_ranked);
    say_ranked("# point " + point.directory + ": " + to_string(r.status) +
               (r.reason.empty() ? "" : " (" + r.reason + ")"));
    encode(mine, point.index, r);
  }
  const std::string all = gather_text(mine.str());
  if (rank != 0) return {0, false};
  std::vector<std::optional<SweepPointResult>> known(points.size());
  decode(all, known);
  write_sweep_summary(dir, parameters, points, known);
  std::size_t completed = 0;
  for (const auto& r : known) completed += r && r->status == SweepPointResult::Status::Completed;
  say("# wrote " + dir + "/sweep.json and sweep.csv: " + std::to_string(completed) + " of " +
      std::to_string(points.size()) + " points completed");
  if (completed == points.size()) return {0, true};
  std::fprintf(stderr, "growshell: %zu of %zu sweep points did not complete (sweep.json says why)\n",
               points.size() - completed, points.size());
  return {3, true};
}

}  // namespace

bool launched_by_mpi_launcher() {
  for (const char* variable : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
    if (std::getenv(variable)) return true;
  return false;
}

RankedSweepOutcome run_sweep_on_ranks(const Scene& base,
                                      const std::vector<SweepParameter>& parameters,
                                      const std::string& dir, ExistingOutput existing,
                                      const std::function<void(const std::string&)>& say) {
  MPI_Init(nullptr, nullptr);
  RankedSweepOutcome code;
  try {
    code = sweep(base, parameters, dir, existing, say);
  } catch (const std::exception& e) {
    // A failure inside the collective part cannot be recovered on one rank alone.
    std::fprintf(stderr, "growshell: error on rank %d: %s\n", world_rank(), e.what());
    MPI_Abort(MPI_COMM_WORLD, 2);
  }
  MPI_Finalize();
  return code;
}

}  // namespace growshell
