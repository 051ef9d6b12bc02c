#pragma once
/// \file
/// The on-disk record of a traced branch, in one directory DIR:
///   - DIR/branch.csv: a header row of column names, then one row of numbers per converged
///     sample (12 significant digits), each row appended whole with one write;
///   - DIR/states/point_NNNNN.state: every converged sample's state (studies/saved_state.hpp);
///   - DIR/events.json: a JSON array of the special points and events, one object per line;
///   - DIR/branch.pvd and its VTK snapshots, and other VTK files (e.g. mode shapes);
///   - DIR/record.json: what of all this has been committed (the number of rows, the next
///     state's index and the last saved state, a summary of every event, the snapshots and the
///     other VTK files). It is rewritten after every saved state, so it marks the point a
///     record can be continued from after a crash.
/// Every file except branch.csv is written whole to a temporary and renamed
/// (studies/atomic_file.hpp), so none is ever seen half-written.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "libshell/io/vtk_writer.hpp"
#include "solvers/continuation/pseudo_arclength.hpp"

namespace growshell {

/// One event as the record summarises it in record.json (events.json holds its full text).
struct RecordedEvent {
  std::string kind;    ///< e.g. "branch_point", "fold", "contact", "eb_max"
  double phi_e = 0.0;  ///< where it was located
  /// The branch it was found on, e.g. "flat" or "cone"; empty when unknown (an event adopted
  /// from a directory written before record.json existed).
  std::string branch;
  /// Named values that belong to it, e.g. {"eb_hat", 4.26} at a maximum of E_b-hat.
  std::vector<std::pair<std::string, double>> values;

  /// The value called `name`, if the event has one.
  std::optional<double> value(const std::string& name) const;
};

/// A special point as a study records it: the fields of its events.json object (kind, phi_e,
/// multiplicity, negative_before, negative_after, bracket), without the braces so that a study
/// can add its own, and its summary for record.json on `branch`.
std::string special_point_event_fields(const SpecialPoint& point);
RecordedEvent special_point_summary(const SpecialPoint& point, const std::string& branch);

/// A branch record in a directory (see the file comment).
class BranchRecord {
 public:
  /// How a record is opened.
  enum class Start {
    /// A new record: DIR and DIR/states are created; the states, snapshots and VTK files of an
    /// earlier record there (as its record.json lists them) are removed; branch.csv gets the
    /// header, events.json an empty list.
    Fresh,
    /// Continues the record in DIR from its last commit: rows, events, states, snapshots and
    /// temporaries written after it (by a run that was killed) are dropped, and the files are
    /// cut back to it. A directory without record.json but with a branch.csv (written before
    /// record.json existed) is adopted as it is: all its rows and events, the states from
    /// point_00000 on up to the first missing one, no snapshots. A directory with neither
    /// starts a fresh record.
    Continue,
  };

  /// Opens the record in `directory` with the given branch.csv columns. Throws
  /// std::runtime_error naming the file if a record to continue has other columns, fewer
  /// rows or events than it committed, a missing last state, or a file that cannot be read
  /// or written.
  BranchRecord(std::string directory, std::vector<std::string> columns, Start start);

  /// The file of the record's commits, in its directory: "record.json".
  static constexpr const char* kRecordFileName = "record.json";

  /// Whether `directory` holds a committed record (a record.json).
  static bool exists(const std::string& directory);

  /// The last saved state the record in `directory` committed (relative path), empty if it
  /// has none; reads record.json only. Throws std::runtime_error naming the file if it is
  /// missing or not a branch record.
  static std::string committed_last_state(const std::string& directory);

  const std::string& directory() const { return directory_; }
  const std::vector<std::string>& columns() const { return columns_; }

  // ---- branch.csv ----
  /// Appends one row (one value per column) with one write. The record keeps the values as
  /// they read back from the file (12 significant digits), so a continued record holds the
  /// same numbers as one written in one go. Throws std::invalid_argument for a row of the
  /// wrong length.
  void append_row(const std::vector<double>& values);
  std::size_t rows() const { return rows_.size(); }
  /// The value in row `row` (0 = first after the header) of column `column`. Throws
  /// std::out_of_range naming the column or row if there is none.
  double value(std::size_t row, const std::string& column) const;

  // ---- states/ ----
  /// Index the next saved state gets (point_NNNNN.state).
  int next_state_index() const { return next_state_; }
  /// Saves the sample as states/point_NNNNN.state (the next index), with the fingerprint of
  /// its model (save_branch_state; 0 = none), and returns that path relative to the directory.
  std::string save_state(const BranchSample& sample, std::uint64_t model_fingerprint = 0);
  /// The last saved state (relative path), empty if there is none.
  const std::string& last_state() const { return last_state_; }

  // ---- events.json ----
  /// Adds an event: `json_object` is its full text (one line, a JSON object) for events.json,
  /// which is rewritten at once; `summary` what record.json keeps of it.
  void add_event(const std::string& json_object, RecordedEvent summary);
  const std::vector<RecordedEvent>& events() const { return events_; }

  // ---- VTK files ----
  /// Writes `surface` as DIR/file_name and lists it in branch.pvd at time phi_e.
  void add_snapshot(double phi_e, const std::string& file_name, const SurfaceSnapshot& surface);
  /// Writes `surface` as DIR/file_name without listing it in branch.pvd (e.g. a mode shape).
  void write_surface(const std::string& file_name, const SurfaceSnapshot& surface);
  std::size_t snapshots() const { return snapshots_.size(); }

  /// Writes record.json: everything recorded so far is committed.
  void commit();

 private:
  void start_fresh();
  void continue_committed();
  void adopt_uncommitted();
  void rewrite_events() const;
  void rewrite_collection() const;
  std::string path(const std::string& name) const { return directory_ + "/" + name; }

  std::string directory_;
  std::vector<std::string> columns_;
  std::vector<std::vector<double>> rows_;
  std::vector<std::string> event_lines_;
  std::vector<RecordedEvent> events_;
  std::vector<CollectionEntry> snapshots_;
  std::vector<std::string> surfaces_;
  int next_state_ = 0;
  std::string last_state_;
};

}  // namespace growshell
