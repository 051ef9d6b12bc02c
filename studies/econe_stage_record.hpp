#pragma once
/// \file
/// What the econe_contact study's stages 2-6 found, kept beside their branch records in
/// DIR/stages.json, so that a resumed study takes each finished stage from the record instead
/// of tracing it again (docs/guide/econe_contact.md, "Resuming").
///
/// The branch records (DIR/symmetric, DIR/skewed, DIR/turned) hold every sample; what they do
/// not hold is how each trace ended and what the skewed search found. The stage record holds
/// that, tied by a key to the scene and to the cone's last state the stages started from: a
/// study resumed with another scene (e.g. continuation.phi_max raised) or from another start
/// traces stages 2-6 again. A stage's entry is written (atomically) only after the stage has
/// committed its branch records, so an entry always describes complete records; a study
/// killed during a stage traces that stage again and keeps the stages before it.
///
/// Format (JSON, format 1):
///   {"format": 1, "key": "<16 hex digits>",
///    "contact_branches": {...} | null,   (stages 2-4: the fields listed at EconeStageRecord)
///    "turned": {...} | null,             (stage 5)
///    "hard_contact": [{"branch": ..., "at": ..., "check": {...}}, ...]}   (stage 6)
/// Numbers are written in their shortest round-trip form, so what is read back is the double
/// that was written, bit for bit; a non-finite number is written as null and read as NaN.

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "libshell/io/scene.hpp"
#include "solvers/contact/econe_branches.hpp"
#include "solvers/continuation/pseudo_arclength.hpp"
#include "studies/hard_contact_check.hpp"

namespace growshell {

/// The highest stable sample of a branch that breaks S4 (where the winding may start): its
/// saved state (path relative to the study directory), phi_e and E_s + E_b + P (J).
struct EconeTopSample {
  std::string state;
  double phi_e = 0.0;
  double energy = 0.0;
};

/// How one trace ended.
struct EconeTraceEnd {
  bool reached_bound = false;
  std::string message;
};

/// What stages 2-6 found beyond their branch records.
struct EconeStageRecord {
  /// econe_stage_key of the scene and the start the stages were computed from.
  std::uint64_t key = 0;

  /// Stages 2-4: the summary of trace_econe_branches that the study's key values are made
  /// from, with the samples in the records. Of `traced`, only these fields are kept:
  /// symmetric, skewed_down and skewed_up (reached_bound and message), first_contact and
  /// stability_loss (parameter), skewed_found, skewed_message, skewed_relaxed_energy,
  /// symmetric_top_energy, skew_search_parameter, crossings (parameter, energy,
  /// slope_difference, error_estimate), crossing_skewed_stable, skewed_search_seconds and the
  /// Ipopt check's fields.
  struct ContactBranches {
    EconeBranchResult traced;
    std::optional<double> max_s4_defect_symmetric;
    std::optional<EconeTopSample> top_skewed;
  };
  std::optional<ContactBranches> contact_branches;

  /// Stage 5: the turned cone's two traces (absent: not traced, or not finished).
  struct Turned {
    EconeTraceEnd down, up;
    std::optional<double> lowest_phi_breaking_s4;
    std::optional<EconeTopSample> top;
  };
  std::optional<Turned> turned;

  /// Stage 6: each finished check, by branch and requested phi_e (the state's x left out).
  struct HardContactPoint {
    std::string branch;
    double at = 0.0;
    HardContactCheck check;
  };
  std::vector<HardContactPoint> hard_contact;

  /// The recorded check of `branch` at `at` (compared exactly), if there is one.
  const HardContactCheck* hard_contact_at(const std::string& branch, double at) const;
};

/// The key of stages 2-6: the FNV-1a hash of the scene (as scene_to_json writes it, without
/// the output keys and the keys of the stages after 6: study.compare_modes, study.wind_to and
/// study.wind_shapes_at; study.hard_contact_at is matched point by point) and of the start's
/// phi_e and x, bit for bit.
std::uint64_t econe_stage_key(const Scene& scene, const BranchSample& start);

/// The record as JSON text (see the file comment), ending with a newline.
std::string econe_stage_record_json(const EconeStageRecord& record);

/// The record the JSON text describes. Throws std::runtime_error starting with `origin` and
/// naming the problem for text that is not a stage record of format 1 (malformed JSON, a
/// missing or mistyped key).
EconeStageRecord parse_econe_stage_record(const std::string& text, const std::string& origin);

/// Reads the record in `path`; std::nullopt if there is no such file. Throws as
/// parse_econe_stage_record, with the path as origin, or std::runtime_error if it cannot be read.
std::optional<EconeStageRecord> read_econe_stage_record(const std::string& path);

/// Writes the record to `path` atomically (write_file_atomically).
void write_econe_stage_record(const std::string& path, const EconeStageRecord& record);

}  // namespace growshell
