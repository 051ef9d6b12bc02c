#include "studies/cone_branch_study.hpp"

#include <Eigen/Core>
#include <chrono>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <memory>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "libshell/analysis/rim_folds.hpp"
#include "libshell/io/shell_snapshot.hpp"
#include "solvers/continuation/cone_branch_entry.hpp"
#include "solvers/continuation/phase_condition_trace.hpp"
#include "solvers/continuation/phase_conditioned_family.hpp"
#include "solvers/continuation/subspace_branch_trace.hpp"
#include "solvers/newton/rigid_motion_pinning.hpp"
#include "studies/atomic_file.hpp"
#include "studies/branch_record.hpp"
#include "studies/cone_branch_events.hpp"
#include "studies/cone_branch_key_values.hpp"
#include "studies/cone_mirror_subspace.hpp"
#include "studies/cone_sample_measures.hpp"
#include "studies/pattern_orientation_check.hpp"
#include "studies/pattern_phase.hpp"
#include "studies/saved_state.hpp"
#include "studies/scene_arclength_corrector.hpp"
#include "studies/scene_contact_penalty.hpp"
#include "studies/special_point_modes.hpp"
#include "studies/study_directory.hpp"
#include "studies/turn_free_stability_index.hpp"

namespace growshell {
namespace {

/// The columns of the cone's branch.csv.
const std::vector<std::string> kConeStudyColumns = {
    "phi_e",     "E_stretch",  "E_bend",      "Eb_hat",
    "area",      "min_gap",    "n_negative",  "corrector_iterations",
    "arclength", "folds",      "core_radius", "s4_defect",
    "chord_up",  "chord_down", "phase_force"};

/// printf into a string: one line of the log.
[[gnu::format(printf, 1, 2)]] std::string line_printf(const char* format, ...) {
  va_list args;
  va_start(args, format);
  va_list copy;
  va_copy(copy, args);
  const int n = std::vsnprintf(nullptr, 0, format, copy);
  va_end(copy);
  std::string out(static_cast<std::size_t>(std::max(n, 0)), '\0');
  std::vsnprintf(out.data(), out.size() + 1, format, args);
  va_end(args);
  return out;
}

std::string shortest(double v) {
  std::ostringstream o;
  o << std::setprecision(17) << v;
  return o.str();
}

void validate_options(const ConeBranchStudyOptions& o) {
  const auto fail = [](const std::string& what) {
    throw std::invalid_argument("cone_branch study: " + what);
  };
  if (!(std::isfinite(o.tolerance) && o.tolerance > 0.0))
    fail("tolerance = " + shortest(o.tolerance) + " must be finite and > 0");
  if (!(o.max_tangent_angle > 0.0 && o.max_tangent_angle < std::numbers::pi))
    fail("max_tangent_angle = " + shortest(o.max_tangent_angle) + " must be in (0, pi)");
  if (!(std::isfinite(o.core_radius) && o.core_radius >= 0.0))
    fail("core_radius = " + shortest(o.core_radius) + " must be finite and >= 0");
  if (o.eigenmodes < 0) fail("eigenmodes = " + std::to_string(o.eigenmodes) + " must be >= 0");
  if (!(std::isfinite(o.symmetry_threshold) && o.symmetry_threshold > 0.0))
    fail("symmetry_threshold = " + shortest(o.symmetry_threshold) + " must be finite and > 0");
  if (o.start == ConeBranchStart::SavedState && o.resume_file.empty())
    fail("a start from a saved state needs resume_file");
}

/// "point_NNNNN": the name of the index-th saved state without its extension.
std::string point_stem(int index) {
  const std::string name = saved_state_name(index);
  return name.substr(0, name.rfind('.'));
}

/// One run of the study: the model, the trace's callbacks and the record they write.
class ConeBranchRun {
 public:
  ConeBranchRun(const Scene& scene, const ConeBranchStudyOptions& options, std::string out_dir,
                const StudyProgress& progress);
  ConeBranchStudy run();

 private:
  void say(const std::string& line) const {
    if (progress_) progress_(line);
  }
  void set_up();
  void open_record();
  void on_sample(const BranchSample& s);
  void record_symmetry_lost(const BranchSample& s, const ConeSampleMeasures& m);
  void on_special(const SpecialPoint& sp);
  void on_event(const LocatedEvent& e);
  void snapshot(double phi, const Eigen::VectorXd& x, const std::string& name);
  int index_without_pattern_turn(const BranchSample& s);
  double phase_force(const BranchSample& s);
  ArclengthOptions cone_arclength_options();
  BranchTrace trace_cone(const Eigen::VectorXd& x0, double phi0, const Eigen::VectorXd& dx,
                         double dphi);
  BranchTrace resume_cone(const BranchSample& saved, const Eigen::VectorXd& dx, double dphi);
  bool trace_from_flat(BranchTrace& trace);
  BranchTrace trace_from_state();
  ConeBranchStudy finish(const BranchTrace& trace, bool entered_cone, double wall);
  std::optional<ConeBranchResults::Orientation> check_orientation(double phi);

  Scene scene_;
  ConeBranchStudyOptions options_;
  std::string out_dir_;
  StudyProgress progress_;
  double h_ = 0.0;
  double contact_distance_ = 0.0;
  std::unique_ptr<ShellModel> model_;
  std::vector<Eigen::Index> pinned_;
  std::shared_ptr<const SymmetricSubspace> subspace_;
  std::unique_ptr<TurnFreeStabilityIndex> turn_free_index_;  ///< index_excludes_pattern_turn
  /// The same index class by class for the samples traced in the subspace (null without one).
  std::unique_ptr<SymmetryClassStabilityIndex> class_index_;
  /// The phase condition's functional, unit length, where the cone is traced in the full space
  /// with one (empty otherwise).
  Eigen::VectorXd phase_functional_;
  ArclengthOptions arclength_;
  std::unique_ptr<ConeSampleMeasurer> measures_;
  std::vector<BranchEvent> events_;
  std::unique_ptr<BranchRecord> record_;
  std::string start_note_;    ///< why a resumed study starts from flat after all
  BranchSample start_state_;  ///< the saved state a resumed study starts from
  std::string start_state_path_;
  std::uint64_t model_fingerprint_ = 0;  ///< scene_model_fingerprint, stored with every state
  std::string branch_ = "flat";          ///< the branch the trace is on, for the recorded events
  bool skip_next_sample_ = false;
  double arclength_offset_ = 0.0;
  int samples_ = 0;  ///< samples recorded on the cone (for output.snapshot_every)
  bool symmetry_lost_ = false;
  double previous_phi_ = std::numeric_limits<double>::quiet_NaN();
  double previous_defect_ = std::numeric_limits<double>::quiet_NaN();
  TraceCost flat_cost_;
};

ConeBranchRun::ConeBranchRun(const Scene& scene, const ConeBranchStudyOptions& options,
                             std::string out_dir, const StudyProgress& progress)
    : scene_(scene), options_(options), out_dir_(std::move(out_dir)), progress_(progress) {
  if (out_dir_.empty()) throw std::invalid_argument("cone_branch study: no output directory");
  scene_.output.directory = out_dir_;
  validate_scene(scene_);
  validate_options(options_);
  // Everything that can fail on bad input comes before the first file is written: the model
  // (e.g. a missing mesh.file), the recorded scene and the saved state to resume from.
  model_ = std::make_unique<ShellModel>(scene_mesh(scene_), scene_model_settings(scene_));
  model_fingerprint_ = scene_model_fingerprint(scene_);
  // Every sample counts its folds on the rim: a rim too coarse for that is refused now, not
  // after the flat branch has been traced.
  try {
    (void)analyze_rim_folds(*model_, model_->reference_positions());
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("the mesh is too coarse to count the cone's folds: ") +
                                e.what() + " (refine it: mesh.size_slope or mesh.rings)");
  }
  if (options_.start == ConeBranchStart::LastState) {
    if (!BranchRecord::exists(out_dir_)) {
      options_.start = ConeBranchStart::Flat;
      start_note_ = "no study record in " + out_dir_ + " to resume: starting from flat";
    } else {
      check_resumable_scene(out_dir_, scene_);
      start_state_path_ = BranchRecord::committed_last_state(out_dir_);
      if (start_state_path_.empty()) {
        options_.start = ConeBranchStart::Flat;
        start_note_ = "the record in " + out_dir_ + " has no saved state yet: starting from flat";
      } else {
        start_state_path_ = out_dir_ + "/" + start_state_path_;
      }
    }
  } else if (options_.start == ConeBranchStart::SavedState) {
    start_state_path_ = options_.resume_file;
  }
  if (options_.start == ConeBranchStart::Flat &&
      scene_.continuation.direction == ContinuationDirection::Backward)
    throw std::invalid_argument(
        "continuation.direction = backward needs a start from a saved state (trace_disc "
        "--resume FILE): a study from the flat sheet grows forward");
  if (options_.start != ConeBranchStart::Flat)
    start_state_ = load_branch_state(start_state_path_, model_->dimension(), model_fingerprint_);
}

/// The model's pins, family, subspace, step control, measures and events; the first lines of
/// the log.
void ConeBranchRun::set_up() {
  h_ = thickness_at_radius(scene_.thickness, 0.0, scene_.geometry.radius);
  contact_distance_ = scene_.physics.contact_distance.value_or(h_);
  const bool ring = scene_.geometry.shape == SceneShape::Ring;
  say(line_printf("# %s R = %g%s, h = %g, mode %d, %lld elements, %lld unknowns",
                  ring ? "ring" : "disc", scene_.geometry.radius,
                  ring ? (", R_i = " + std::to_string(scene_.geometry.inner_radius)).c_str() : "",
                  h_, scene_.continuation.mode, static_cast<long long>(model_->num_elements()),
                  static_cast<long long>(model_->dimension())));
  if (!start_note_.empty()) say("# " + start_note_);

  // Rigid motions: pins on the mesh's mirror axes, so that symmetric states stay symmetric.
  const Eigen::VectorXd& X = model_->reference_positions();
  const Eigen::MatrixX3d P =
      Eigen::Map<const Eigen::Matrix<double, -1, 3, Eigen::RowMajor>>(X.data(), X.size() / 3, 3);
  pinned_ = mirror_axis_pinned_dofs(P, model_->sheet_vertices(), model_->settings().growth.center);
  if (options_.index_excludes_pattern_turn)
    turn_free_index_ = std::make_unique<TurnFreeStabilityIndex>(*model_, *model_, pinned_);
  if (options_.symmetric_subspace) {
    ConeSubspaceChoice choice =
        cone_mirror_subspace(*model_, scene_.geometry.radius, scene_.continuation.mode);
    if (!choice.note.empty()) say("# " + choice.note);
    subspace_ = std::move(choice.subspace);
    if (subspace_ && turn_free_index_ && subspace_->group().classes_split_space())
      class_index_ = std::make_unique<SymmetryClassStabilityIndex>(*model_, subspace_->group());
  }
  arclength_.initial_step = scene_.continuation.max_step / 4;
  arclength_.max_step = scene_.continuation.max_step;
  arclength_.min_step = scene_.continuation.min_step;
  arclength_.gradient_tolerance = options_.tolerance * model_->natural_force_scale();
  arclength_.max_tangent_angle = options_.max_tangent_angle;
  arclength_.corrector = scene_arclength_corrector(scene_);
  arclength_.parameter_min = scene_.continuation.phi_min;
  arclength_.parameter_max = scene_.continuation.phi_max;

  ConeMeasureSettings measure;
  measure.exclusion_radius = resolved_exclusion_radius(scene_);
  measure.core_radius = options_.core_radius;
  measure.measure_symmetry = scene_.continuation.mode == 2;
  measures_ = std::make_unique<ConeSampleMeasurer>(*model_, measure);
  events_ = cone_branch_events(*measures_, contact_distance_, !options_.through_contact);
}

/// Opens the record: a fresh one from flat, else the recorded one continued, with the state of
/// the trace it holds (the symmetry test's last point, the arclength).
void ConeBranchRun::open_record() {
  const bool fresh = options_.start == ConeBranchStart::Flat;
  // A study's other outputs describe the record as it was: stale once it changes.
  for (const char* stale : {"results.json", "cost.json", "eb_hat.png"})
    std::filesystem::remove(out_dir_ + "/" + stale);
  record_ = std::make_unique<BranchRecord>(
      out_dir_, kConeStudyColumns,
      fresh ? BranchRecord::Start::Fresh : BranchRecord::Start::Continue);
  if (fresh) return;
  branch_ = "cone";
  samples_ = static_cast<int>(record_->rows());
  for (const RecordedEvent& e : record_->events())
    if (e.kind == "symmetry_lost") symmetry_lost_ = true;
  if (record_->rows() > 0) {
    previous_phi_ = record_->value(record_->rows() - 1, "phi_e");
    previous_defect_ = record_->value(record_->rows() - 1, "s4_defect");
  }
  if (options_.start == ConeBranchStart::LastState) {
    skip_next_sample_ = true;  // the start is the last recorded row, corrected once more
    if (record_->rows() > 0) arclength_offset_ = record_->value(record_->rows() - 1, "arclength");
  }
}

void ConeBranchRun::on_sample(const BranchSample& s) {
  if (skip_next_sample_) {
    skip_next_sample_ = false;
    return;
  }
  const ConeSampleMeasures m = measures_->measure(s);
  say(line_printf("%9.5f %13.6e %13.6e %10.5f %10.3e %4d %3d %5d", s.parameter, m.stretching,
                  m.bending, m.eb_hat, m.min_gap, s.negative_eigenvalues, s.corrector_iterations,
                  m.folds));
  if (!m.symmetry_note.empty())
    say(line_printf("# no S4 defect at phi_e = %.7f: %s", s.parameter, m.symmetry_note.c_str()));
  record_->append_row({s.parameter, m.stretching, m.bending, m.eb_hat, m.area, m.min_gap,
                       static_cast<double>(s.negative_eigenvalues),
                       static_cast<double>(s.corrector_iterations), s.arclength + arclength_offset_,
                       static_cast<double>(m.folds), m.core_radius, m.s4_defect, m.chord_up,
                       m.chord_down, phase_force(s)});
  if (!symmetry_lost_ && m.s4_defect > options_.symmetry_threshold) record_symmetry_lost(s, m);
  previous_phi_ = s.parameter;
  previous_defect_ = m.s4_defect;
  const int index = record_->next_state_index();
  record_->save_state(s, model_fingerprint_);
  const int every = scene_.output.snapshot_every;
  if (every > 0 && samples_ % every == 0) snapshot(s.parameter, s.x, point_stem(index) + ".vtu");
  ++samples_;
  record_->commit();
}

/// symmetry_lost, once, at the first point whose S4 defect exceeds the threshold: with the
/// previous point (below it) and the linear estimate of the crossing.
void ConeBranchRun::record_symmetry_lost(const BranchSample& s, const ConeSampleMeasures& m) {
  symmetry_lost_ = true;
  const double threshold = options_.symmetry_threshold;
  std::ostringstream j;
  j << std::setprecision(10) << "{\"kind\": \"symmetry_lost\", \"phi_e\": " << s.parameter
    << ", \"s4_defect\": " << m.s4_defect << ", \"chord_up\": " << m.chord_up
    << ", \"chord_down\": " << m.chord_down << ", \"threshold\": " << threshold
    << ", \"state\": \"states/" << saved_state_name(record_->next_state_index()) << "\"";
  RecordedEvent summary{"symmetry_lost", s.parameter, branch_, {{"s4_defect", m.s4_defect}}};
  if (std::isfinite(previous_defect_)) {
    const double crossing = previous_phi_ + (threshold - previous_defect_) /
                                                (m.s4_defect - previous_defect_) *
                                                (s.parameter - previous_phi_);
    j << ", \"previous_phi_e\": " << previous_phi_
      << ", \"previous_s4_defect\": " << previous_defect_ << ", \"phi_e_crossing\": " << crossing;
    summary.values.emplace_back("phi_e_crossing", crossing);
  }
  j << "}";
  record_->add_event(j.str(), std::move(summary));
  say(
      line_printf("# event symmetry_lost at phi_e = %.7f (S4 defect %.3e > %.3e, chords %.5f up, "
                  "%.5f down)",
                  s.parameter, m.s4_defect, threshold, m.chord_up, m.chord_down));
}

void ConeBranchRun::on_special(const SpecialPoint& sp) {
  int special_index = 0;  // special points recorded before this one (their mode files' names)
  for (const RecordedEvent& e : record_->events())
    if (e.kind == "fold" || e.kind == "branch_point") ++special_index;
  std::ostringstream j;
  j << std::setprecision(10) << "{" << special_point_event_fields(sp);
  if (options_.eigenmodes > 0) {
    // The lowest eigenpairs of the pinned Hessian there, their overlap with the pattern's turn
    // and their mode shapes (the state displaced along each mode by 5 % of R at its largest).
    // The pins are re-chosen on the state where the trace's barely hold its rigid motions, as
    // the stability index does, so that a nearly free spin is not reported as a mode.
    const std::vector<Eigen::Index> pins =
        analysis_pins(*model_, sp.x, pinned_, TurnFreeStabilityIndex::kDefaultMaxPinCondition);
    const SpecialPointModes modes =
        special_point_modes(*model_, sp.x, sp.parameter, pins, options_.eigenmodes);
    j << ", \"orientation_overlap\": [";
    for (std::size_t k = 0; k < modes.orientation_overlap.size(); ++k)
      j << (k ? ", " : "") << modes.orientation_overlap[k];
    j << "]";
    j << ", \"eigenvalues\": [";
    for (Eigen::Index k = 0; k < modes.pairs.values.size(); ++k) {
      j << (k ? ", " : "") << modes.pairs.values(k);
      if (scene_.output.write_vtk) {
        const Eigen::VectorXd shape =
            displaced_along_mode(sp.x, modes.pairs.vectors.col(k), 0.05 * scene_.geometry.radius);
        record_->write_surface(
            "special_" + std::to_string(special_index) + "_mode_" + std::to_string(k) + ".vtu",
            shell_snapshot(*model_, shape, sp.parameter, 1));
      }
    }
    j << "]";
  }
  j << "}";
  record_->add_event(j.str(), special_point_summary(sp, branch_));
  say(line_printf("# %s at phi_e = %.7f (multiplicity %d, negative %d -> %d)", to_string(sp.kind),
                  sp.parameter, sp.multiplicity, sp.negative_before, sp.negative_after));
}

void ConeBranchRun::on_event(const LocatedEvent& e) {
  RecordedEvent summary{e.kind, e.parameter, branch_, {}};
  if (e.kind == "eb_max")
    summary.values.emplace_back("eb_hat", measures_->eb_hat(e.x, e.parameter));
  std::ostringstream j;
  j << std::setprecision(10) << "{\"kind\": \"" << e.kind << "\", \"phi_e\": " << e.parameter
    << ", \"bracket\": " << e.bracket_width << "}";
  record_->add_event(j.str(), std::move(summary));
  say(line_printf("# event %s at phi_e = %.7f", e.kind.c_str(), e.parameter));
  snapshot(e.parameter, e.x, "event_" + e.kind + ".vtu");
}

void ConeBranchRun::snapshot(double phi, const Eigen::VectorXd& x, const std::string& name) {
  if (!scene_.output.write_vtk) return;
  record_->add_snapshot(phi, name, shell_snapshot(*model_, x, phi, 2));
}

/// The stability index of a full cone state without the pattern's turn: the pinned Hessian's
/// negative count on the hyperplane orthogonal to the turn; the plain count where the state
/// is axisymmetric to within 1e-9 R (no pattern, so nothing to turn).
int ConeBranchRun::index_without_pattern_turn(const BranchSample& s) {
  if (!class_index_ || s.reduced_x.size() != subspace_->dimension())
    return turn_free_index_->at(s.x, s.parameter);
  // Class by class at the sample's state in the subspace's frame, where the mirrors are the
  // coordinate planes.
  return turn_free_index_by_class(*class_index_, *model_, subspace_->expand(s.reduced_x),
                                  s.parameter);
}

/// |mu|: the force (N) with which the phase condition holds the sample's pattern, the gradient's
/// component along the unit functional over the free dofs; NaN without a phase condition.
double ConeBranchRun::phase_force(const BranchSample& s) {
  if (phase_functional_.size() != s.x.size() || branch_ != "cone")
    return std::numeric_limits<double>::quiet_NaN();
  Eigen::VectorXd g;
  model_->evaluate(s.x, s.parameter, &g, nullptr);
  return std::abs(phase_multiplier(g, phase_functional_, pinned_));
}

/// The continuation settings of the cone's trace: the study's, with the stability index that
/// leaves out the pattern's turn if asked.
ArclengthOptions ConeBranchRun::cone_arclength_options() {
  ArclengthOptions options = arclength_;
  if (turn_free_index_)
    options.stability_index = [this](const BranchSample& s) {
      return index_without_pattern_turn(s);
    };
  return options;
}

/// The cone branch from (x0, phi0) along (dx, dphi), in the subspace if there is one (full
/// states in and out either way); in the full space with the pattern's orientation held by a
/// phase condition if asked.
BranchTrace ConeBranchRun::trace_cone(const Eigen::VectorXd& x0, double phi0,
                                      const Eigen::VectorXd& dx, double dphi) {
  const auto sample = [this](const BranchSample& s) { on_sample(s); };
  const auto special = [this](const SpecialPoint& sp) { on_special(sp); };
  const auto event = [this](const LocatedEvent& e) { on_event(e); };
  const ArclengthOptions options = cone_arclength_options();
  if (subspace_)
    return trace_branch_in_subspace(*model_, *subspace_, x0, phi0, dx, dphi, pinned_, options,
                                    sample, special, events_, event);
  if (options_.phase_condition) {
    const Eigen::VectorXd c = pattern_phase_functional(*model_, x0, dx, scene_.continuation.mode);
    phase_functional_ = c / c.norm();
    return trace_branch_with_phase_condition(*model_, phase_functional_, x0, phi0, dx, dphi,
                                             pinned_, options, sample, special, events_, event);
  }
  return trace_branch_along(*model_, x0, phi0, dx, dphi, pinned_, options, sample, special, events_,
                            event);
}

/// The cone on from a saved sample: in the subspace from the reduced coordinates it keeps
/// (resume_branch_in_subspace), so that the trace goes on through the samples the
/// interrupted one would have found; otherwise as trace_cone from its state.
BranchTrace ConeBranchRun::resume_cone(const BranchSample& saved, const Eigen::VectorXd& dx,
                                       double dphi) {
  if (!subspace_) return trace_cone(saved.x, saved.parameter, dx, dphi);
  const auto sample = [this](const BranchSample& s) { on_sample(s); };
  const auto special = [this](const SpecialPoint& sp) { on_special(sp); };
  const auto event = [this](const LocatedEvent& e) { on_event(e); };
  bool reduced = false;
  BranchTrace trace = resume_branch_in_subspace(*model_, *subspace_, saved, dx, dphi, pinned_,
                                                cone_arclength_options(), sample, special,
                                                events_, event, &reduced);
  if (!reduced)
    say("# the saved state keeps no reduced coordinates of this subspace: its projection is "
        "traced on (the same branch, with steps equal to rounding)");
  return trace;
}

/// The flat branch to the branch point of the wanted mode, then the cone; false (with the
/// reason in trace.message) if there is no such branch point.
bool ConeBranchRun::trace_from_flat(BranchTrace& trace) {
  ConeEntryOptions entry_options;
  entry_options.folds = scene_.continuation.mode;
  entry_options.phi_start = scene_.continuation.phi_start;
  entry_options.thickness = h_;
  entry_options.radius = scene_.geometry.radius;
  const ConeBranchEntry entry =
      enter_cone_branch(*model_, *model_, entry_options, pinned_, arclength_,
                        [this](const SpecialPoint& sp) { on_special(sp); });
  flat_cost_ = entry.flat.cost;
  if (!entry.found) {
    trace.message = entry.message;
    return false;
  }
  say(line_printf("# switching onto the %d-fold cone at phi_e = %.7f", scene_.continuation.mode,
                  entry.branch_point.parameter));
  // The branch point the cone leaves from (results.json's phi_branch): the flat branch may
  // have passed others first (the modes below n, or the other half of a split pair).
  {
    std::ostringstream j;
    j << std::setprecision(10) << "{\"kind\": \"cone_entry\", \"phi_e\": "
      << entry.branch_point.parameter << ", \"mode\": " << scene_.continuation.mode << "}";
    record_->add_event(j.str(), {"cone_entry", entry.branch_point.parameter, "flat",
                                 {{"mode", static_cast<double>(scene_.continuation.mode)}}});
  }
  branch_ = "cone";
  const BranchPointDeparture departure =
      leave_branch_point(entry, [&](const Eigen::VectorXd& start, const Eigen::VectorXd& mode) {
        return trace_cone(start, entry.branch_point.parameter, mode, 0.0);
      });
  if (departure.attempts > 1)
    say(
        line_printf("# the corrector converged onto the cone at a step off the branch point of "
                    "%.3g, after %d larger ones failed",
                    departure.switch_step, departure.attempts - 1));
  trace = departure.trace;
  return true;
}

/// The cone from a saved state: forward or backward from any state, or on from the last one.
BranchTrace ConeBranchRun::trace_from_state() {
  const BranchSample& start = start_state_;
  double sign = 1.0;  // the last state: on in the direction the trace had there
  if (options_.start == ConeBranchStart::SavedState)
    sign = scene_.continuation.direction == ContinuationDirection::Backward
               ? (start.tangent_parameter > 0 ? -1.0 : 1.0)
               : (start.tangent_parameter >= 0 ? 1.0 : -1.0);
  say(line_printf("# resuming from %s at phi_e = %.6f", start_state_path_.c_str(),
                  start.parameter));
  if (options_.start == ConeBranchStart::LastState && !options_.through_contact) {
    for (const RecordedEvent& e : record_->events()) {
      if (e.kind != "contact") continue;
      // The recorded trace stopped there; going on would only find that contact again.
      say(
          line_printf("# the recorded trace stopped at contact at phi_e = %.7f (set "
                      "study.through_contact to go on)",
                      e.phi_e));
      BranchTrace done;
      done.last = start;
      done.reached_bound = true;
      // The uninterrupted trace's message, so that the resumed record's results.json says
      // what it said.
      done.message = "stopped at event 'contact'";
      return done;
    }
  }
  ConeSubspaceChoice choice = subspace_for_start(subspace_, start.x, 0.1 * h_);
  if (!choice.note.empty()) say("# " + choice.note);
  subspace_ = std::move(choice.subspace);
  // Resumed, the trace takes the step the interrupted one would have taken next, so that it
  // goes on through the same samples (a state saved before the step was recorded has 0).
  if (options_.start == ConeBranchStart::LastState && start.next_step >= arclength_.min_step &&
      start.next_step <= arclength_.max_step)
    arclength_.initial_step = start.next_step;
  return resume_cone(start, sign * start.tangent_state, sign * start.tangent_parameter);
}

ConeBranchStudy ConeBranchRun::finish(const BranchTrace& trace, bool entered_cone, double wall) {
  ConeBranchStudy out;
  out.entered_cone = entered_cone;
  if (entered_cone) snapshot(trace.last.parameter, trace.last.x, "last.vtu");
  // Where the time went (flat branch + cone), also written to DIR/cost.json.
  TraceCost& c = out.cost;
  c = flat_cost_;
  c += trace.cost;
  out.steps = trace.steps;
  out.failed_steps = trace.failed_steps;
  say(line_printf(
      "# cost: %.1f s wall, %d linearisations (assembly %.1f s), %d LDL^T "
      "factorisations with inertia (%.1f s), %d solves (%.1f s), %d stability indices (%.1f s), "
      "events %.1f s, output %.1f s",
      wall, c.linearizations, c.assembly_seconds, c.factorizations, c.factorization_seconds,
      c.solves, c.solve_seconds, c.stability_evaluations, c.stability_seconds, c.event_seconds,
      c.callback_seconds));
  std::ostringstream cost;
  cost << std::setprecision(6) << "{\"wall_seconds\": " << wall
       << ", \"cone_steps\": " << trace.steps << ", \"failed_steps\": " << trace.failed_steps
       << ", \"linearizations\": " << c.linearizations
       << ", \"factorizations\": " << c.factorizations << ", \"solves\": " << c.solves
       << ", \"gradient_evaluations\": " << c.gradient_evaluations
       << ", \"chord_fallbacks\": " << c.chord_fallbacks
       << ", \"assembly_seconds\": " << c.assembly_seconds
       << ", \"factorization_seconds\": " << c.factorization_seconds
       << ", \"solve_seconds\": " << c.solve_seconds
       << ", \"stability_evaluations\": " << c.stability_evaluations
       << ", \"stability_seconds\": " << c.stability_seconds
       << ", \"event_seconds\": " << c.event_seconds
       << ", \"output_seconds\": " << c.callback_seconds << "}\n";
  write_file_atomically(out_dir_ + "/cost.json", cost.str());
  say(line_printf("# trace ended: %s (%d steps, %d failed)", trace.message.c_str(), trace.steps,
                  trace.failed_steps));

  ConeBranchResults& r = out.results;
  r.thickness = h_;
  r.mode = scene_.continuation.mode;
  r.mesh.family = mesh_family_name(scene_.mesh.family);
  if (graded_by_size(scene_.mesh.family)) r.mesh.size_slope = scene_.mesh.size_slope;
  r.mesh.elements = static_cast<long long>(model_->num_elements());
  r.mesh.unknowns = static_cast<long long>(model_->dimension());
  set_cone_branch_key_values(*record_, r);
  if (entered_cone && scene_.study.orientation_check_at)
    r.orientation = check_orientation(*scene_.study.orientation_check_at);
  r.completed = entered_cone && trace.reached_bound;
  r.end = trace.message;
  r.wall_seconds = wall;
  record_->commit();
  write_cone_branch_results(out_dir_, r);
  say(line_printf("# wrote %s/branch.csv, events.json, states/, branch.pvd, results.json",
                  out_dir_.c_str()));
  return out;
}

/// study.orientation_check_at: the saved state nearest phi turned against the mesh, relaxed and
/// compared (studies/pattern_orientation_check.hpp); the lowest turned state, if any converged.
std::optional<ConeBranchResults::Orientation> ConeBranchRun::check_orientation(double phi) {
  const std::optional<BranchSample> nearest =
      nearest_saved_state(out_dir_, phi, model_->dimension(), model_fingerprint_);
  if (!nearest) return std::nullopt;
  const BranchSample& state = *nearest;
  const ContactProxy proxy = scene_contact_proxy(scene_, *model_);
  const PatternOrientationCheckOptions o = scene_orientation_check_options(scene_, *model_, proxy);
  PatternOrientationCheck check;
  try {
    check = check_pattern_orientation(*model_, proxy, state.x, state.parameter, pinned_, o);
  } catch (const std::invalid_argument& e) {
    // A state without fold directions (the flat sheet below the branch point) has no pattern
    // to turn: the trace's results stand without the check.
    say(line_printf("# no orientation check at phi_e = %.6f: %s", state.parameter, e.what()));
    return std::nullopt;
  }
  constexpr double kDeg = 180.0 / std::numbers::pi;
  std::optional<ConeBranchResults::Orientation> lowest;
  for (const TurnedPatternState& t : check.turned) {
    say(t.converged
            ? line_printf("# orientation at phi_e = %.6f: turned %.3f deg, settled at %.3f deg, "
                          "energy %+.4f %% against the traced state, S4 defect %.3e",
                          check.phi_e, t.turn * kDeg, t.fold_angle * kDeg,
                          100.0 * t.energy_relative, t.s4_defect)
            : line_printf("# orientation at phi_e = %.6f: turned %.3f deg, relaxation failed: %s",
                          check.phi_e, t.turn * kDeg, t.message.c_str()));
    if (!t.converged || (lowest && t.energy_relative >= lowest->energy_relative)) continue;
    lowest = ConeBranchResults::Orientation{
        check.phi_e, t.turn * kDeg, t.fold_angle * kDeg,  t.energy_relative,      t.s4_defect,
        t.chord_up,  t.chord_down,  t.energy_change_core, t.energy_change_outside};
  }
  return lowest;
}

ConeBranchStudy ConeBranchRun::run() {
  std::filesystem::create_directories(out_dir_);
  write_file_atomically(out_dir_ + "/scene.json", scene_to_json(scene_));
  set_up();
  open_record();
  say(line_printf("%9s %13s %13s %10s %10s %4s %3s %5s", "phi_e", "E_stretch", "E_bend", "Eb_hat",
                  "min_gap", "neg", "it", "folds"));
  const auto wall_start = std::chrono::steady_clock::now();
  BranchTrace trace;
  bool entered_cone = true;
  if (options_.start == ConeBranchStart::Flat)
    entered_cone = trace_from_flat(trace);
  else
    trace = trace_from_state();
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return finish(trace, entered_cone, wall);
}

}  // namespace

ConeBranchStudyOptions cone_branch_study_options(const Scene& scene) {
  ConeBranchStudyOptions o;
  o.tolerance = scene.study.tolerance;
  o.max_tangent_angle = scene.study.max_tangent_angle;
  o.core_radius = scene.study.core_radius;
  o.eigenmodes = scene.study.eigenmodes;
  o.symmetric_subspace = scene.study.symmetric_subspace;
  o.index_excludes_pattern_turn = scene.study.index_excludes_pattern_turn;
  o.phase_condition = scene.study.phase_condition;
  o.symmetry_threshold = scene.study.symmetry_threshold;
  o.through_contact = scene.study.through_contact;
  return o;
}

ConeBranchStudy run_cone_branch_study(const Scene& scene, const ConeBranchStudyOptions& options,
                                      const std::string& out_dir, const StudyProgress& progress) {
  return ConeBranchRun(scene, options, out_dir, progress).run();
}

}  // namespace growshell
