#include "studies/econe_contact_study.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <limits>
#include <memory>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "libshell/analysis/cone_symmetry.hpp"
#include "libshell/analysis/contact_zones.hpp"
#include "libshell/contact/contact_penalty.hpp"
#include "libshell/contact/contact_proxy.hpp"
#include "libshell/io/contact_snapshot.hpp"
#include "libshell/io/shell_snapshot.hpp"
#include "solvers/contact/contact_growth_path.hpp"
#include "solvers/contact/econe_branches.hpp"
#include "solvers/contact/hard_contact_solve_options.hpp"
#include "solvers/continuation/turning_back_event.hpp"
#include "solvers/newton/rigid_motion_pinning.hpp"
#include "studies/atomic_file.hpp"
#include "studies/branch_record.hpp"
#include "studies/cone_branch_study.hpp"
#include "studies/cone_mirror_subspace.hpp"
#include "studies/econe_contact_cost.hpp"
#include "studies/econe_stage_record.hpp"
#include "studies/econe_winding_options.hpp"
#include "studies/ground_state_exchange.hpp"
#include "studies/hard_contact_check.hpp"
#include "studies/pattern_orientation_check.hpp"
#include "studies/pattern_phase.hpp"
#include "studies/saved_state.hpp"
#include "studies/scene_arclength_corrector.hpp"
#include "studies/scene_contact_penalty.hpp"
#include "studies/turn_free_stability_index.hpp"

namespace growshell {
namespace {

namespace fs = std::filesystem;

/// The columns of DIR/symmetric/branch.csv and DIR/skewed/branch.csv.
const std::vector<std::string> kContactStudyColumns = {"phi_e",         "E_stretch",
                                                       "E_bend",        "E_penalty",
                                                       "Eb_hat",        "area",
                                                       "min_distance",  "active_pairs",
                                                       "contact_force", "gamma",
                                                       "n_negative",    "dE_dphi",
                                                       "arclength",     "corrector_iterations",
                                                       "s4_defect",     "chord_up",
                                                       "chord_down",    "phase_force"};

constexpr const char* kConeDir = "cone";

/// How close in phi_e the downward traces of the skewed and turned cones end before their
/// folds once a step fails there (ArclengthOptions::fold_approach_tolerance). Next to these
/// folds the correctors fail at any step length, and without it each fold cost a halving
/// down to the minimum step (docs/performance.md, "Folds approached").
constexpr double kFoldApproachTolerance = 1e-4;

/// The cone_branch study of stage 7 for the n-fold cone: stage 1's, with mode n, in DIR/cone_nN.
Scene compared_mode_scene(const Scene& scene, int n) {
  Scene mode = econe_contact_cone_scene(scene);
  mode.continuation.mode = n;
  mode.study.orientation_check_at.reset();  // the two-fold cone's S4 check
  mode.output.directory = (fs::path(scene.output.directory) / ("cone_n" + std::to_string(n))).string();
  return mode;
}

/// Whether an S4 defect (relative to R) says the state is not S4-symmetric: above the scene's
/// threshold, and below half the radius, beyond which the measure failed (fold directions not
/// found on a turned state) rather than found a cone. One rule for the skewed search, the
/// skewed samples and the orientation warning.
bool breaks_s4(double defect, double threshold) { return defect > threshold && defect < 0.5; }

/// A step test (ArclengthOptions::accept_step) for the traces of a cone that breaks S4: a step
/// whose end has no measurable S4 defect, or one a thousandth of its start's or less, has
/// snapped onto another branch (the S4-symmetric cone; measured: from 4e-3 to 2e-9 in one step
/// next to the turned cone's fold at h = 0.04), not followed this one, whose defect changes
/// by a few per cent a step. A step's start is mostly the last step's end, whose defect is kept.
std::function<bool(const BranchSample&, const BranchSample&)> s4_breaking_step(
    std::shared_ptr<const ConeSymmetryMeter> meter) {
  struct Measured {
    Eigen::VectorXd x;
    double defect = 0.0;
  };
  auto last = std::make_shared<Measured>();
  return [meter, last](const BranchSample& from, const BranchSample& to) {
    try {
      const Measured previous = std::exchange(*last, Measured{to.x, meter->s4(to.x).defect});
      const double after = last->defect;
      if (!(after < 0.5)) return false;
      const bool known = previous.x.size() == from.x.size() && previous.x == from.x;
      return after >= 1e-3 * (known ? previous.defect : meter->s4(from.x).defect);
    } catch (const std::exception&) {
      return false;
    }
  };
}

/// The phase condition of a cone with `folds` folds traced in the full space: its fold
/// pattern's orientation about the axis at `start` (studies/pattern_phase.hpp), held so that
/// the corners of the faceted contact surface cannot turn the nearly free pattern
/// (docs/contact.md, "The pattern's turn in the full space").
Eigen::VectorXd cone_phase_functional(const ShellModel& model, const Eigen::VectorXd& start,
                                      int folds) {
  return pattern_phase_functional(model, start, start, folds);
}

std::string fixed(double v, int digits) {
  std::ostringstream o;
  o << std::fixed << std::setprecision(digits) << v;
  return o.str();
}

/// One run of the study: stage 1 delegated to the cone_branch study, stages 2-4 here.
class EconeContactRun {
 public:
  EconeContactRun(const Scene& scene, ExistingOutput existing, const StudyProgress& progress);
  EconeContactResults run();

 private:
  void say(const std::string& line) const {
    if (progress_) progress_(line);
  }
  void trace_cone();
  void set_up_contact();
  void check_orientation();
  std::vector<BranchEnergySample> saved_energies(const std::string& directory, double from,
                                                 double below) const;
  std::vector<BranchEnergySample> cone_energies(double below) const;
  /// Writes the sample to `record` (row and state) and the log; returns its S4 defect (NaN
  /// for a state without fold directions).
  double record_sample(const char* branch, BranchRecord& record, const ContactBranchSample& s);
  void record_special(const char* branch, BranchRecord& record, const SpecialPoint& sp);
  void summarize(const EconeBranchResult& traced);
  void trace_turned();
  EconeStageRecord::Turned trace_turned_branch(double phi0);
  void measure_turned(EconeTurnedBranch turned);
  void check_hard_contact_points();
  void trace_compared_modes();
  void wind_up();
  void measure_energy_ratios();
  void report_phase_forces();
  BranchRecord& record(EconeBranch which) {
    return which == EconeBranch::Symmetric ? *symmetric_ : *skewed_;
  }
  /// The symmetric branch's samples (the contact-free cone ahead of the trace with contact,
  /// then the traced branch), and the skewed cone's samples that break S4.
  std::vector<BranchStateSample> symmetric_samples() const;
  /// The same, by increasing phi_e (for branch_energy_at).
  std::vector<BranchStateSample> symmetric_samples_by_phi() const;
  /// Leaves the study incomplete, `why` added to results.json's end.
  void mark_incomplete(const std::string& why) {
    results_.end = results_.completed ? why : results_.end + "; " + why;
    results_.completed = false;
  }
  /// Adds `why` to results.json's end as a note: "completed (why)", or to the notes there
  /// ("completed (...; why)"), or to the reasons of an incomplete study.
  void add_note(const std::string& why) {
    if (!results_.completed)
      results_.end += "; " + why;
    else if (results_.end == "completed")
      results_.end = "completed (" + why + ")";
    else
      results_.end.insert(results_.end.size() - 1, "; " + why);
  }
  std::vector<BranchStateSample> skewed_samples() const;
  /// The phi_e of the skewed branch's special points (where its stability changes).
  std::vector<double> skewed_special_points() const;

  Scene scene_;
  ExistingOutput existing_;
  StudyProgress progress_;
  std::string dir_;
  double h_ = 0.0;
  std::unique_ptr<ShellModel> model_;
  /// The S4 defect and chords of the model's states, its mesh-dependent part prepared at the
  /// first use (symmetry()).
  std::shared_ptr<const ConeSymmetryMeter> symmetry_;
  const std::shared_ptr<const ConeSymmetryMeter>& symmetry() {
    if (!symmetry_) symmetry_ = std::make_shared<const ConeSymmetryMeter>(*model_);
    return symmetry_;
  }
  std::uint64_t fingerprint_ = 0;
  std::vector<Eigen::Index> pinned_;
  std::unique_ptr<ContactProxy> proxy_;
  EconeBranchOptions options_;
  BranchSample start_;  ///< the cone's last state
  std::unique_ptr<BranchRecord> symmetric_, skewed_, turned_, wound_;
  /// What this run spent on the stages with contact (DIR/contact_cost.json).
  EconeContactCost cost_;
  void count_trace(const char* name, const ContactBranchTrace& trace) {
    if (trace.steps == 0 && trace.cost.continuation.linearizations == 0) return;  // not traced
    cost_.traces.push_back({name, trace.steps, trace.failed_steps, trace.cost});
  }
  /// The highest stable sample that breaks S4 of the skewed and of the turned branch: where
  /// the winding may start.
  struct TopSample {
    Eigen::VectorXd x;
    double phi = -std::numeric_limits<double>::infinity();
    double energy = 0.0;  ///< E_s + E_b + P
    std::string state;    ///< its saved state, relative to the study directory
  };
  TopSample top_skewed_, top_turned_;
  /// Keeps the sample just recorded in `branch` (its state the record's last) if it is the
  /// highest stable one that breaks S4 so far.
  void keep_if_top(TopSample& top, const ContactBranchSample& s, double defect,
                   const BranchRecord& branch) const {
    if (s.sample.negative_eigenvalues == 0 && breaks_s4(defect, scene_.study.symmetry_threshold) &&
        s.sample.parameter > top.phi)
      top = {s.sample.x, s.sample.parameter,
             s.stretching_energy + s.bending_energy + s.penalty_energy,
             fs::path(branch.directory()).filename().string() + "/" + branch.last_state()};
  }
  /// The top sample as the stage record keeps it, and back (its state read from disk).
  static std::optional<EconeTopSample> recorded_top(const TopSample& top) {
    if (top.x.size() == 0) return std::nullopt;
    return EconeTopSample{top.state, top.phi, top.energy};
  }
  TopSample restored_top(const std::optional<EconeTopSample>& top) const {
    if (!top) return {};
    const BranchSample s =
        load_branch_state(dir_ + "/" + top->state, model_->dimension(), fingerprint_);
    return {s.x, top->phi_e, top->energy, top->state};
  }
  /// Stages 2-4 traced, or taken from the stage record of a resumed study.
  EconeBranchResult contact_branches();
  std::string stage_record_path() const { return dir_ + "/stages.json"; }
  /// Writes stages_ to stage_record_path() with what recorded_ holds of the stages this run
  /// has not reached yet (still valid: recorded_ is dropped before a stage is traced again),
  /// so that a kill between two stages loses no finished one.
  void save_stages() const;
  /// What this run's stages 2-6 found so far (written to stage_record_path() after each), and
  /// what a resumed study's record holds for the same scene and start (empty otherwise).
  /// The half-turn subspace of the skewed and turned cone (null: the full space).
  std::shared_ptr<const SymmetricSubspace> half_turn_;
  EconeStageRecord stages_;
  std::optional<EconeStageRecord> recorded_;
  /// The orientation check's lowest relaxed state that breaks S4 (empty if none): the start of
  /// the turned branch.
  Eigen::VectorXd turned_start_;
  double turned_turn_deg_ = 0.0;
  double turned_energy_relative_ = std::numeric_limits<double>::infinity();
  EconeContactResults results_;
};

EconeContactRun::EconeContactRun(const Scene& scene, ExistingOutput existing,
                                 const StudyProgress& progress)
    : scene_(scene), existing_(existing), progress_(progress), dir_(scene.output.directory) {
  validate_scene(scene_);
  // The cone_branch studies of stages 1 and 7, before anything is written.
  validate_scene(econe_contact_cone_scene(scene_));
  for (const int n : scene_.study.compare_modes) validate_scene(compared_mode_scene(scene_, n));
  if (scene_.study.kind != StudyKind::EconeContact)
    throw std::invalid_argument("run_econe_contact_study: the scene's study.kind is " +
                                study_kind_name(scene_.study.kind) + ", not econe_contact");
  if (scene_.continuation.mode != 2)
    throw std::invalid_argument(
        "continuation.mode = " + std::to_string(scene_.continuation.mode) +
        ": the econe_contact study follows the two-fold cone and its skewed cone (mode 2)");
  if (scene_.continuation.direction != ContinuationDirection::Forward)
    throw std::invalid_argument(
        "continuation.direction = backward: the econe_contact study grows from the flat sheet");
  check_econe_contact_directory(dir_, existing_);
  // The model (a missing mesh file, a mesh that cannot be built) before anything is written.
  model_ = std::make_unique<ShellModel>(scene_mesh(scene_), scene_model_settings(scene_));
  fingerprint_ = scene_model_fingerprint(scene_);
  h_ = thickness_at_radius(scene_.thickness, 0.0, scene_.geometry.radius);
  if (existing_ == ExistingOutput::Resume && fs::exists(fs::path(dir_) / kConeDir / "scene.json"))
    check_resumable_scene((fs::path(dir_) / kConeDir).string(), econe_contact_cone_scene(scene_));
  // A resumed study's record of stages 2-6, read (and a malformed one refused) before
  // anything is written; its key is compared once the cone has given the start (run()).
  if (existing_ == ExistingOutput::Resume) recorded_ = read_econe_stage_record(stage_record_path());
}

/// Stage 1: the contact-free cone up to first contact, and its last state.
void EconeContactRun::trace_cone() {
  const Scene cone_scene = econe_contact_cone_scene(scene_);
  const std::string cone_dir = cone_scene.output.directory;
  ConeBranchStudyOptions options = cone_branch_study_options(cone_scene);
  if (existing_ == ExistingOutput::Resume) options.start = ConeBranchStart::LastState;
  say("# stage 1: the cone without contact up to first contact, into " + cone_dir);
  const ConeBranchStudy cone = run_cone_branch_study(cone_scene, options, cone_dir, progress_);
  results_.phi_branch = cone.results.phi_branch;
  results_.phi_first_contact = cone.results.phi_gap_h;
  results_.phi_max = cone.results.phi_max;
  results_.eb_hat_max = cone.results.eb_hat_max;
  if (!cone.entered_cone)
    throw std::runtime_error("the flat sheet has no two-fold branch point below phi_max: " +
                             cone.results.end);
  const std::string last = BranchRecord::committed_last_state(cone_dir);
  if (last.empty()) throw std::runtime_error(cone_dir + " holds no state to go on from");
  start_ = load_branch_state(cone_dir + "/" + last, model_->dimension(), fingerprint_);
  results_.phi_contact_start = start_.parameter;
}

/// The settings of stages 2-4 (from the scene), the proxy and the pins.
void EconeContactRun::set_up_contact() {
  const SceneStudy& st = scene_.study;
  const Eigen::VectorXd& X = model_->reference_positions();
  const Eigen::MatrixX3d P =
      Eigen::Map<const Eigen::Matrix<double, -1, 3, Eigen::RowMajor>>(X.data(), X.size() / 3, 3);
  // The cone study's pins (on the mesh's mirror axes), so that symmetric states stay symmetric.
  pinned_ = mirror_axis_pinned_dofs(P, model_->sheet_vertices(), model_->settings().growth.center);
  proxy_ = std::make_unique<ContactProxy>(scene_contact_proxy(scene_, *model_));

  options_.contact = scene_contact_penalty(scene_, *model_, *proxy_);
  ContactBranchOptions& c = options_.contact;
  c.arclength.initial_step = st.contact_max_step / 4;
  c.arclength.max_step = st.contact_max_step;
  c.arclength.min_step = 1e-6;
  c.arclength.gradient_tolerance = st.tolerance * model_->natural_force_scale();
  c.arclength.max_tangent_angle = 0.5;
  c.arclength.corrector = scene_arclength_corrector(scene_);
  // A corrector that needs more iterations converges, next to the skewed and turned cones'
  // folds, onto another branch (docs/performance.md, "Failed steps of the traces with contact").
  c.arclength.max_corrector_iterations = st.contact_max_corrector_iterations;
  // A segment's start (the last sample on a rebuilt pair set) keeps the continuation's default.
  c.arclength.start_corrector_iterations = ArclengthOptions{}.max_corrector_iterations;
  c.arclength.stall_iterations = st.contact_stall_iterations;
  c.arclength.growth_pause_after_failure = st.contact_growth_pause;
  // Every triangle near a vertex (as the winding's), or its nearest where the set is built.
  c.selection.nearest_triangle_only =
      st.contact_vertex_triangles == SceneContactVertexTriangles::NearestAtBuild;
  // The penalty's Hessian jumps where a pair enters contact, so the tangent may turn by a
  // finite angle over any step: short steps are accepted on a converged corrector alone.
  c.arclength.angle_test_max_step = 0.02 * st.contact_max_step;
  c.start_relaxation = scene_penalty_relaxation(scene_, *model_);
  if (st.index_excludes_pattern_turn) {
    // Per segment: class by class for the samples traced in a subspace whose group splits the
    // space, else the full Hessian's count with its analysis kept over the segment.
    const ShellModel& model = *model_;
    const std::vector<Eigen::Index> pins = pinned_;
    c.stability_index_for_segment = [&model, pins](const ParametrizedObjective& energy,
                                                   const SymmetricSubspace* subspace) {
      auto full = std::make_shared<TurnFreeStabilityIndex>(energy, model, pins);
      std::shared_ptr<SymmetryClassStabilityIndex> by_class;
      if (subspace && subspace->group().classes_split_space())
        by_class = std::make_shared<SymmetryClassStabilityIndex>(energy, subspace->group());
      return [full, by_class, subspace, &model](const BranchSample& s) {
        if (by_class && s.reduced_x.size() == subspace->dimension())
          return turn_free_index_by_class(*by_class, model, subspace->expand(s.reduced_x),
                                          s.parameter);
        return full->at(s.x, s.parameter);
      };
    };
  }
  if (st.symmetric_subspace) {
    ConeSubspaceChoice choice = cone_mirror_subspace(*model_, scene_.geometry.radius, 2);
    if (!choice.note.empty()) say("# " + choice.note);
    choice = subspace_for_start(std::move(choice.subspace), start_.x, 0.1 * h_);
    if (!choice.note.empty()) say("# " + choice.note);
    c.symmetric_subspace = std::move(choice.subspace);
  }
  if (st.half_turn_subspace) {
    ConeSubspaceChoice choice =
        cone_half_turn_subspace(*model_, scene_.geometry.radius, "the skewed and turned cone");
    if (!choice.note.empty()) say("# " + choice.note);
    half_turn_ = std::move(choice.subspace);
    options_.skewed_subspace = half_turn_;
  }

  options_.symmetric_end = scene_.continuation.phi_max;
  options_.skewed_end = scene_.continuation.phi_max;
  options_.skewed_start = SkewedStart::Top;
  // Down to its fold, where the skewed cone ends: what lies beyond is unstable and not needed
  // for phi_e^crit (docs/performance.md, "Branch jumps and the step control").
  options_.skewed_down_ends_at_fold = true;
  options_.skewed_fold_approach_tolerance = kFoldApproachTolerance;
  options_.skewed_accept_step = s4_breaking_step(symmetry());
  if (st.phase_condition) {
    const ShellModel& model = *model_;
    const int folds = scene_.continuation.mode;
    options_.skewed_phase_functional = [&model, folds](const Eigen::VectorXd& start) {
      return cone_phase_functional(model, start, folds);
    };
  }
  // Down to the cone's maximum of E_b-hat at most: the skewed cone's lower end lies between.
  options_.skewed_min = results_.phi_max.value_or(start_.parameter - 1.0);
  options_.skew_search_at = st.skew_search_at.value_or(std::numeric_limits<double>::quiet_NaN());
  // A relaxed state that keeps S4 is the symmetric cone in another frame (turned about the
  // axis against the mesh), not a skewed cone.
  {
    const double threshold = st.symmetry_threshold;
    options_.accept_skewed = [meter = symmetry(), threshold](const Eigen::VectorXd& x,
                                                             std::string& why_not) {
      double defect = 0.0;
      try {
        defect = meter->s4(x).defect;
      } catch (const std::exception& e) {
        why_not = std::string("no S4 defect (") + e.what() + ")";
        return false;
      }
      if (breaks_s4(defect, threshold)) return true;
      std::ostringstream text;
      if (defect >= 0.5)
        text << "no S4 defect (the measure gave " << defect << ", beyond half the radius)";
      else
        text << "keeps S4 (defect " << defect << "), the symmetric cone turned about its axis";
      why_not = text.str();
      return false;
    };
  }
  options_.relaxation = scene_penalty_relaxation(scene_, *model_);
  if (st.ipopt_check)
    options_.verify_with_ipopt =
        hard_contact_solve_options(*model_, h_, c.contact_distance, c.exclusion_radius,
                                   c.candidate_margin, options_.relaxation);
  options_.symmetric_before = cone_energies(start_.parameter);

  results_.contact_distance = c.contact_distance;
  results_.exclusion_radius = c.exclusion_radius;
  results_.penalty_stiffness = c.stiffness;
  results_.proxy_segments_per_edge = proxy_->segments_per_edge;
  results_.proxy_vertices = proxy_->num_vertices();
  results_.contact_surface = c.gap.limit_surface ? "limit_surface" : "proxy_triangles";
  say("# stage 2: contact distance " + fixed(c.contact_distance, 5) + " m, exclusion radius " +
      fixed(c.exclusion_radius, 5) + " m (" + fixed(c.exclusion_radius / h_, 3) +
      " h), penalty k = " + fixed(c.stiffness, 1) + " N/m, proxy of " +
      std::to_string(proxy_->num_vertices()) + " vertices");
}

/// The pattern of the contact start turned against the mesh, relaxed and compared
/// (study.orientation_check_turns); each relaxed state is kept in DIR/orientation/.
void EconeContactRun::check_orientation() {
  const std::vector<double>& turns_deg = scene_.study.orientation_check_turns;
  if (turns_deg.empty()) return;
  // The penalty and the relaxation as every study runs the check: the penalty is this study's.
  const PatternOrientationCheckOptions o =
      scene_orientation_check_options(scene_, *model_, *proxy_);
  say("# orientation check at phi_e = " + fixed(start_.parameter, 6) + ": the pattern turned by " +
      std::to_string(turns_deg.size()) + " angle(s) against the mesh and relaxed");
  const PatternOrientationCheck check =
      check_pattern_orientation(*model_, *proxy_, start_.x, start_.parameter, pinned_, o);
  constexpr double kDeg = 180.0 / std::numbers::pi;
  EconeOrientationCheck r;
  r.phi_e = check.phi_e;
  r.fold_angle_deg = check.fold_angle * kDeg;
  r.s4_defect = check.s4_defect;
  r.core_radius = o.core_radius;
  const fs::path dir = fs::path(dir_) / "orientation";
  fs::create_directories(dir);
  for (const TurnedPatternState& t : check.turned) {
    EconeOrientationCheck::Turned e;
    e.turn_deg = t.turn * kDeg;
    e.converged = t.converged;
    e.message = t.message;
    if (t.converged) {
      e.fold_angle_deg = t.fold_angle * kDeg;
      e.energy_relative = t.energy_relative;
      e.s4_defect = t.s4_defect;
      e.chord_up = t.chord_up;
      e.chord_down = t.chord_down;
      e.energy_change_core = t.energy_change_core;
      e.energy_change_outside = t.energy_change_outside;
      e.lowest_eigenvalue = t.lowest_eigenvalue;
      e.turn_free_index = t.turn_free_index;
      BranchSample sample;
      sample.parameter = check.phi_e;
      sample.x = t.x;
      sample.tangent_state = Eigen::VectorXd::Zero(t.x.size());
      e.state = "orientation/turn_" + fixed(e.turn_deg, 3) + ".state";
      save_branch_state(dir_ + "/" + e.state, sample, fingerprint_);
    }
    say("# turned " + fixed(e.turn_deg, 3) + " deg: " +
        (t.converged
             ? "settled at " + fixed(e.fold_angle_deg, 3) + " deg, energy " +
                   fixed(100.0 * e.energy_relative, 4) + " % against the traced state, S4 " +
                   fixed(e.s4_defect, 5) + ", change inside h " + fixed(e.energy_change_core, 6) +
                   " J, outside " + fixed(e.energy_change_outside, 6) + " J, turn-free index " +
                   std::to_string(e.turn_free_index)
             : "relaxation failed: " + t.message));
    // A lower state that breaks S4: the traced symmetric cone is not the sheet's lowest state
    // here, and energy comparisons with it depend on the mesh (docs/results.md, "The apex core
    // against the mesh").
    if (t.converged && -e.energy_relative > options_.energy_margin &&
        breaks_s4(e.s4_defect, scene_.study.symmetry_threshold)) {
      std::ostringstream w;
      w << "orientation: the pattern turned by " << e.turn_deg
        << " deg against the mesh relaxed at phi_e = " << fixed(check.phi_e, 4) << " to a state "
        << fixed(-100.0 * e.energy_relative, 3)
        << " % below the traced symmetric cone that breaks S4 (defect " << fixed(e.s4_defect, 5)
        << "; energy change inside r = h " << fixed(e.energy_change_core, 6) << " J, outside "
        << fixed(e.energy_change_outside, 6)
        << " J): the symmetric branch, traced with its folds on the mesh's mirror lines, is "
           "not the sheet's lowest state; the study traces the turned state (turned/) and "
           "measures phi_crit_energy against it";
      results_.warnings.push_back(w.str());
      say("# warning: " + w.str());
      if (e.energy_relative < turned_energy_relative_) {
        turned_start_ = t.x;
        turned_turn_deg_ = e.turn_deg;
        turned_energy_relative_ = e.energy_relative;
      }
    }
    r.turned.push_back(std::move(e));
  }
  results_.orientation_check = std::move(r);
}

/// The energies and slopes of the saved states in `directory` with phi_e in (from, below), by
/// increasing phi_e (a later state that does not increase it is skipped), each evaluated
/// without contact.
std::vector<BranchEnergySample> EconeContactRun::saved_energies(const std::string& directory,
                                                                double from, double below) const {
  std::vector<BranchEnergySample> out;
  for (const fs::path& file : saved_state_files(directory)) {
    const BranchSample s = load_branch_state(file.string(), model_->dimension(), fingerprint_);
    if (!(s.parameter > from && s.parameter < below)) continue;
    if (!out.empty() && !(s.parameter > out.back().parameter)) continue;
    const ContactBranchSample d =
        describe_contact_sample(*model_, *proxy_, s, ContactCandidates{}, options_.contact);
    out.push_back({s.parameter, d.stretching_energy + d.bending_energy, d.energy_slope});
  }
  return out;
}

/// The contact-free cone's energies and slopes below `below`, by increasing phi_e from its
/// branch point on: the symmetric branch ahead of the trace with contact, for the crossing.
std::vector<BranchEnergySample> EconeContactRun::cone_energies(double below) const {
  return saved_energies((fs::path(dir_) / kConeDir).string(), results_.phi_branch.value_or(0.0),
                        below);
}

double EconeContactRun::record_sample(const char* branch, BranchRecord& r,
                                      const ContactBranchSample& s) {
  double gamma = std::numeric_limits<double>::quiet_NaN(), force = 0.0;
  if (!s.pairs.empty() && s.active_pairs > 0) {
    const ContactGapConstraints gaps(*proxy_, s.pairs, options_.contact.contact_distance,
                                     model_->dimension(), options_.contact.gap);
    gamma = cone_contact_plane_angle(gaps, s.sample.x, s.forces, scene_.geometry.radius);
    force = s.forces.sum();
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  double defect = nan, up = nan, down = nan;
  try {
    const ConeSymmetry measured = symmetry()->measure(s.sample.x);
    defect = measured.s4.defect;
    up = measured.chords.chord_up;
    down = measured.chords.chord_down;
  } catch (const std::exception&) {
    // A state without fold directions has no S4 defect: NaN in the record.
  }
  char line[256];
  std::snprintf(line, sizeof line, "%-9s %9.5f %12.5e %12.5e %10.3e %8.4f %3d %7.4f %5d %9.2e %3d",
                branch, s.sample.parameter, s.stretching_energy, s.bending_energy,
                s.penalty_energy, s.normalized_bending, s.sample.negative_eigenvalues, gamma,
                s.active_pairs, defect, s.sample.corrector_iterations);
  if (!std::isnan(s.phase_force)) {
    const std::size_t used = std::strlen(line);
    std::snprintf(line + used, sizeof line - used, "  phase force %.2e", s.phase_force);
  }
  say(line);
  r.append_row({s.sample.parameter, s.stretching_energy, s.bending_energy, s.penalty_energy,
                s.normalized_bending, s.current_area, s.min_distance,
                static_cast<double>(s.active_pairs), force, gamma,
                static_cast<double>(s.sample.negative_eigenvalues), s.energy_slope,
                s.sample.arclength, static_cast<double>(s.sample.corrector_iterations), defect, up,
                down, s.phase_force});
  r.save_state(s.sample, fingerprint_);
  r.commit();
  return defect;
}

void EconeContactRun::record_special(const char* branch, BranchRecord& r, const SpecialPoint& sp) {
  std::string json = "{";
  json += special_point_event_fields(sp);
  json += "}";
  r.add_event(json, special_point_summary(sp, branch));
  say("# " + std::string(branch) + " branch: " + to_string(sp.kind) + " at phi_e = " +
      fixed(sp.parameter, 7) + " (negative " + std::to_string(sp.negative_before) + " -> " +
      std::to_string(sp.negative_after) + ")");
  r.commit();
}

/// The rows of `record` whose S4 defect `keep` accepts, as (phi_e, E_s + E_b + P, negative).
std::vector<BranchStateSample> record_samples(const BranchRecord& record,
                                              const std::function<bool(double)>& keep) {
  std::vector<BranchStateSample> out;
  for (std::size_t row = 0; row < record.rows(); ++row)
    if (keep(record.value(row, "s4_defect")))
      out.push_back({record.value(row, "phi_e"),
                     record.value(row, "E_stretch") + record.value(row, "E_bend") +
                         record.value(row, "E_penalty"),
                     static_cast<int>(record.value(row, "n_negative"))});
  return out;
}

std::vector<BranchStateSample> EconeContactRun::symmetric_samples() const {
  std::vector<BranchStateSample> out;
  for (const BranchEnergySample& c : options_.symmetric_before)
    out.push_back({c.parameter, c.energy, 0});
  for (const BranchStateSample& s : record_samples(*symmetric_, [](double) { return true; }))
    out.push_back(s);
  return out;
}

std::vector<BranchStateSample> EconeContactRun::symmetric_samples_by_phi() const {
  std::vector<BranchStateSample> out = symmetric_samples();
  std::sort(out.begin(), out.end(), [](const BranchStateSample& a, const BranchStateSample& b) {
    return a.phi_e < b.phi_e;
  });
  return out;
}

std::vector<BranchStateSample> EconeContactRun::skewed_samples() const {
  const double threshold = scene_.study.symmetry_threshold;
  return record_samples(*skewed_, [threshold](double d) { return breaks_s4(d, threshold); });
}

std::vector<double> EconeContactRun::skewed_special_points() const {
  std::vector<double> out;
  for (const RecordedEvent& e : skewed_->events()) out.push_back(e.phi_e);
  return out;
}

/// The key values of stages 2-4.
void EconeContactRun::summarize(const EconeBranchResult& t) {
  EconeContactResults& r = results_;
  // First contact is the cone's gap = h event (on the limit surface) where the cone stopped
  // there; the penalty's own event (proxy pairs, symmetric/events.json) only if it did not.
  if (!r.phi_first_contact && t.first_contact) r.phi_first_contact = t.first_contact->parameter;
  if (t.stability_loss) r.phi_crit_stability = t.stability_loss->parameter;
  // The skewed trace can run onto the symmetric cone turned against the mesh (at a fold of the
  // skewed branch, or where pairs change): only its samples that break S4 are the skewed cone.
  // A defect above half the radius is a measure that failed (fold directions not found on a
  // turned state), not a cone.
  const std::vector<BranchStateSample> skewed = skewed_samples();
  // A crossing counts if samples that break S4 lie within 0.05 of it on both sides.
  const auto on_skewed_cone = [&skewed](double phi) {
    bool below = false, above = false;
    for (const BranchStateSample& s : skewed) {
      below = below || (s.phi_e <= phi && s.phi_e >= phi - 0.05);
      above = above || (s.phi_e >= phi && s.phi_e <= phi + 0.05);
    }
    return below && above;
  };
  std::vector<double> crossings;
  for (std::size_t i = 0; i < t.crossings.size(); ++i) {
    const double phi = t.crossings[i].parameter;
    if (!on_skewed_cone(phi)) continue;
    const bool stable = i < t.crossing_skewed_stable.size() && t.crossing_skewed_stable[i];
    r.crossings.push_back({phi, t.crossings[i].error_estimate, stable});
    crossings.push_back(phi);
  }
  // The exchange of ground states: the symmetric branch (the cone without contact ahead of the
  // trace with contact; only the skewed branch's stability matters), the skewed cone's samples,
  // and the skewed branch's special points.
  if (const auto exchange =
          ground_state_exchange(symmetric_samples(), skewed, crossings, skewed_special_points())) {
    r.phi_crit_energy = exchange->phi_e;
    r.phi_crit_energy_criterion = exchange->criterion;
  }
  r.skewed_found = t.skewed_found;
  r.skewed_message = t.skewed_message;
  if (t.skewed_found) {
    r.skew_search_at = t.skew_search_parameter;
    if (t.symmetric_top_energy != 0.0)
      r.skewed_energy_below_symmetric =
          (t.symmetric_top_energy - t.skewed_relaxed_energy) / t.symmetric_top_energy;
  }
  for (const BranchStateSample& s : skewed) {
    r.skewed_lowest_phi = std::min(r.skewed_lowest_phi.value_or(s.phi_e), s.phi_e);
    r.skewed_highest_phi = std::max(r.skewed_highest_phi.value_or(s.phi_e), s.phi_e);
  }
  if (t.ipopt_checked) {
    EconeIpoptCheck check;
    check.converged = t.ipopt_converged;
    check.message = t.ipopt_message;
    if (t.ipopt_energy != 0.0)
      check.relative_energy_difference =
          (t.penalty_elastic_energy - t.ipopt_energy) / t.ipopt_energy;
    check.state_difference_over_h = t.ipopt_state_difference / h_;
    check.min_distance_over_h = t.ipopt_min_distance / h_;
    r.ipopt = check;
  }
  std::string end;
  if (!t.symmetric.reached_bound) end = "symmetric branch: " + t.symmetric.message;
  if (!t.skewed_found)
    end += std::string(end.empty() ? "" : "; ") + "no skewed cone: " + t.skewed_message;
  // The downward trace is there to find phi_e^crit by energy: one that ends early after it
  // passed below an exchange it located (not merely its own lowest sample) has done its job,
  // and the end says where it stopped.
  std::string note;
  const bool exchange_located = r.phi_crit_energy &&
                                r.phi_crit_energy_criterion != "lowest_sample" &&
                                r.skewed_lowest_phi && *r.skewed_lowest_phi < *r.phi_crit_energy;
  if (t.skewed_found && skewed_->rows() == 0)
    end += std::string(end.empty() ? "" : "; ") + "the skewed state found did not start a branch";
  for (const auto& [name, trace] :
       {std::pair{"downwards", &t.skewed_down}, std::pair{"upwards", &t.skewed_up}}) {
    // A trace that was run (it has a message) and did not end at a bound; one that ended at
    // its start (no step) counts too.
    if (!t.skewed_found || trace->message.empty() || trace->reached_bound) continue;
    std::string& into = std::string(name) == "downwards" && exchange_located ? note : end;
    into += std::string(into.empty() ? "" : "; ") + "skewed branch " + name + ": " + trace->message;
  }
  r.completed = end.empty();
  r.end = !r.completed ? end : note.empty() ? "completed" : "completed (" + note + ")";
}

void EconeContactRun::save_stages() const {
  EconeStageRecord out = stages_;
  if (recorded_) {
    if (!out.turned) out.turned = recorded_->turned;
    for (const EconeStageRecord::HardContactPoint& p : recorded_->hard_contact)
      if (!out.hard_contact_at(p.branch, p.at)) out.hard_contact.push_back(p);
  }
  write_econe_stage_record(stage_record_path(), out);
}

/// Stages 2-4: the symmetric branch with contact, the skewed search and the skewed branch
/// (trace_econe_branches), recorded in DIR/symmetric and DIR/skewed, and what they found in
/// the stage record; a resumed study whose record holds them takes them from there.
EconeBranchResult EconeContactRun::contact_branches() {
  // Taken from the record only with the branch records it describes (not removed by hand).
  if (recorded_ && recorded_->contact_branches && BranchRecord::exists(dir_ + "/symmetric") &&
      BranchRecord::exists(dir_ + "/skewed")) {
    const EconeStageRecord::ContactBranches& r = *recorded_->contact_branches;
    symmetric_ = std::make_unique<BranchRecord>(dir_ + "/symmetric", kContactStudyColumns,
                                                BranchRecord::Start::Continue);
    skewed_ = std::make_unique<BranchRecord>(dir_ + "/skewed", kContactStudyColumns,
                                             BranchRecord::Start::Continue);
    results_.max_s4_defect_symmetric = r.max_s4_defect_symmetric;
    top_skewed_ = restored_top(r.top_skewed);
    stages_.contact_branches = r;
    say("# stage 2-4: taken from stages.json (" + std::to_string(symmetric_->rows()) +
        " symmetric and " + std::to_string(skewed_->rows()) + " skewed samples recorded)");
    return r.traced;
  }
  // The branches are traced again: what the record held of them and of the stages after them
  // is stale.
  recorded_.reset();
  save_stages();
  symmetric_ = std::make_unique<BranchRecord>(dir_ + "/symmetric", kContactStudyColumns,
                                              BranchRecord::Start::Fresh);
  skewed_ = std::make_unique<BranchRecord>(dir_ + "/skewed", kContactStudyColumns,
                                           BranchRecord::Start::Fresh);
  say("# stage 2-4: the symmetric branch with contact from phi_e = " + fixed(start_.parameter, 6) +
      ", the skewed cone, the crossing");
  char header[256];
  std::snprintf(header, sizeof header, "%-9s %9s %12s %12s %10s %8s %3s %7s %5s %9s %3s", "branch",
                "phi_e", "E_stretch", "E_bend", "E_penalty", "Eb_hat", "neg", "gamma", "n_c", "s4",
                "it");
  say(header);
  EconeBranchCallbacks callbacks;
  callbacks.on_sample = [this](EconeBranch which, const ContactBranchSample& s) {
    const double defect = record_sample(to_string(which), record(which), s);
    if (which == EconeBranch::Symmetric && std::isfinite(defect))
      results_.max_s4_defect_symmetric =
          std::max(results_.max_s4_defect_symmetric.value_or(0.0), defect);
    if (which == EconeBranch::Skewed) keep_if_top(top_skewed_, s, defect, *skewed_);
  };
  callbacks.on_special = [this](EconeBranch which, const SpecialPoint& sp) {
    record_special(to_string(which), record(which), sp);
  };
  callbacks.on_event = [this](const LocatedEvent& e) {
    std::ostringstream j;
    j << std::setprecision(10) << "{\"kind\": \"" << e.kind << "\", \"phi_e\": " << e.parameter
      << ", \"bracket\": " << e.bracket_width << "}";
    symmetric_->add_event(j.str(), {e.kind, e.parameter, "symmetric", {}});
    symmetric_->commit();
    say("# symmetric branch: event " + e.kind + " at phi_e = " + fixed(e.parameter, 7));
  };
  callbacks.on_note = [this](const std::string& text) { say("# " + text); };
  const EconeBranchResult traced = trace_econe_branches(
      *model_, *proxy_, start_.x, start_.parameter, pinned_, options_, callbacks);
  count_trace("symmetric", traced.symmetric);
  count_trace("skewed_down", traced.skewed_down);
  count_trace("skewed_up", traced.skewed_up);
  cost_.skewed_search_seconds = traced.skewed_search_seconds;
  stages_.contact_branches = {traced, results_.max_s4_defect_symmetric, recorded_top(top_skewed_)};
  save_stages();
  return traced;
}

/// Stage 5: the orientation check's lowest turned state that breaks S4, traced with the
/// contact penalty in the full space (its core is free of the mesh's mirror lines), down to
/// where the skewed cone is followed and up to continuation.phi_max; compared with the
/// symmetric branch and with the skewed cone.
void EconeContactRun::trace_turned() {
  // A resumed study's record of the same scene and start holds the traces whole.
  const bool from_record = recorded_ && recorded_->turned && turned_start_.size() > 0 &&
                           BranchRecord::exists(dir_ + "/turned");
  if (!from_record) {
    if (turned_start_.size() > 0) {
      // The record must not describe the turned cone (nor the checks made on its states)
      // while it is traced again.
      recorded_.reset();
      save_stages();
    }
    fs::remove_all(fs::path(dir_) / "turned");  // stale once the branches are traced again
  }
  if (turned_start_.size() == 0) return;
  const double phi0 = results_.orientation_check->phi_e;
  EconeTurnedBranch t;
  t.start_phi = phi0;
  t.turn_deg = turned_turn_deg_;
  EconeStageRecord::Turned traced;
  if (from_record) {
    traced = *recorded_->turned;
    turned_ = std::make_unique<BranchRecord>(dir_ + "/turned", kContactStudyColumns,
                                             BranchRecord::Start::Continue);
    top_turned_ = restored_top(traced.top);
    say("# stage 5: taken from stages.json (" + std::to_string(turned_->rows()) +
        " samples of the turned cone recorded)");
  } else {
    traced = trace_turned_branch(phi0);
  }
  stages_.turned = traced;
  if (!from_record) save_stages();
  t.lowest_phi_breaking_s4 = traced.lowest_phi_breaking_s4;
  t.end = "downwards: " + traced.down.message + "; upwards: " + traced.up.message;
  measure_turned(std::move(t));
  // A trace that ended before its bound leaves the study incomplete, as the other stages do,
  // but for a downward one that ended below the skewed cone's lowest sample: it is there as the
  // skewed cone's reference, and had done that (e.g. stalled next to its fold).
  const std::optional<double> lowest = results_.turned->lowest_phi;
  const bool down_covers_skewed =
      results_.skewed_lowest_phi && lowest && *lowest <= *results_.skewed_lowest_phi;
  for (const auto& [name, trace] :
       {std::pair{"downwards", &traced.down}, std::pair{"upwards", &traced.up}}) {
    if (trace->reached_bound) continue;
    const std::string why = std::string("turned branch ") + name + ": " + trace->message;
    if (std::string(name) == "downwards" && down_covers_skewed)
      add_note(why);
    else
      mark_incomplete(why);
  }
}

/// With study.phase_condition: the largest force the phase condition took up on the skewed and
/// turned cones (branch.csv's phase_force), as a warning where it exceeds the corrector's force
/// tolerance, since those states are then equilibria only up to that load.
void EconeContactRun::report_phase_forces() {
  if (!scene_.study.phase_condition) return;
  const double tolerance = options_.contact.arclength.gradient_tolerance;
  for (const auto& [name, record] :
       {std::pair{"skewed", skewed_.get()}, std::pair{"turned", turned_.get()}}) {
    if (!record) continue;
    double largest = 0.0;  // stays 0 where no row holds a condition (NaN)
    for (std::size_t i = 0; i < record->rows(); ++i) {
      const double f = record->value(i, "phase_force");
      if (!std::isnan(f)) largest = std::max(largest, f);
    }
    if (largest <= tolerance) continue;
    std::ostringstream w;
    w << "phase condition: the " << name << " cone's pattern was held with forces up to "
      << std::setprecision(3) << largest << " N (branch.csv's phase_force), "
      << std::setprecision(2) << largest / tolerance
      << " times the corrector's force tolerance: its states are equilibria of the discrete "
         "problem only up to that load";
    results_.warnings.push_back(w.str());
    say("# warning: " + w.str());
  }
}

/// Stage 5's two traces from the turned state at phi0, into DIR/turned (a fresh record).
EconeStageRecord::Turned EconeContactRun::trace_turned_branch(double phi0) {
  turned_ = std::make_unique<BranchRecord>(dir_ + "/turned", kContactStudyColumns,
                                           BranchRecord::Start::Fresh);
  say("# stage 5: the cone turned by " + fixed(turned_turn_deg_, 3) +
      " deg against the mesh and relaxed at phi_e = " + fixed(phi0, 6) +
      ", traced down and up");
  ContactBranchOptions o = options_.contact;
  // It breaks the mirrors and keeps the half turn.
  ConeSubspaceChoice choice = subspace_for_start(half_turn_, turned_start_,
                                                 0.1 * o.contact_distance, "the turned cone");
  if (!choice.note.empty()) say("# " + choice.note);
  o.symmetric_subspace = std::move(choice.subspace);
  o.arclength.parameter_min = options_.skewed_min;
  o.arclength.parameter_max = options_.symmetric_end;
  o.arclength.max_steps = options_.max_steps_per_branch;
  o.arclength.accept_step = s4_breaking_step(symmetry());
  // Where it is traced in the full space, its pattern's orientation held if the scene asks.
  if (scene_.study.phase_condition && !o.symmetric_subspace)
    o.phase_functional = cone_phase_functional(*model_, turned_start_, scene_.continuation.mode);
  const std::vector<Eigen::Index> pins = rigid_pins_for_state(*model_, turned_start_, pinned_, o);
  const double threshold = scene_.study.symmetry_threshold;
  EconeStageRecord::Turned t;
  bool skip_start = false;  // the upward trace's corrected start is the downward trace's
  const auto on_sample = [&](const ContactBranchSample& s) {
    if (skip_start) {
      skip_start = false;
      return;
    }
    const double defect = record_sample("turned", *turned_, s);
    keep_if_top(top_turned_, s, defect, *turned_);
    if (breaks_s4(defect, threshold))
      t.lowest_phi_breaking_s4 =
          std::min(t.lowest_phi_breaking_s4.value_or(s.sample.parameter), s.sample.parameter);
  };
  const auto on_special = [&](const SpecialPoint& sp) { record_special("turned", *turned_, sp); };
  const Eigen::VectorXd no_direction = Eigen::VectorXd::Zero(model_->dimension());
  // Each trace ends where phi_e turns back, and the downward one also at its first special
  // point: going down, the turned cone ends at a fold (index 0 -> 1, 5.2651 at h = 0.04). Past
  // it lie its unstable half and, a corrector's snap away, the S4-symmetric cone: samples of
  // other branches, which the comparisons below would read as the turned cone's
  // (docs/performance.md, "Branch jumps and the step control").
  ContactBranchOptions down_options = o;
  down_options.arclength.max_special_points = 1;
  down_options.arclength.fold_approach_tolerance = kFoldApproachTolerance;
  const ContactBranchTrace down =
      trace_contact_branch(*model_, *proxy_, turned_start_, phi0, no_direction, -1.0, pins,
                           down_options, on_sample, on_special, {turning_back_event(-1)});
  say("# turned branch, downwards: " + down.message);
  count_trace("turned_down", down);
  skip_start = turned_->rows() > 0;
  const ContactBranchTrace up =
      trace_contact_branch(*model_, *proxy_, turned_start_, phi0, no_direction, 1.0, pins, o,
                           on_sample, on_special, {turning_back_event(+1)});
  say("# turned branch, upwards: " + up.message);
  count_trace("turned_up", up);
  t.down = {down.reached_bound, down.message};
  t.up = {up.reached_bound, up.message};
  t.top = recorded_top(top_turned_);
  return t;
}

/// Stage 5's key values from the turned cone's record: against the symmetric branch and the
/// skewed cone, and phi_crit_energy measured against it.
void EconeContactRun::measure_turned(EconeTurnedBranch t) {
  // Its samples in the order traced (row k of the record) and by phi_e, against the symmetric
  // branch and the skewed cone.
  const auto by_phi = [](const BranchStateSample& a, const BranchStateSample& b) {
    return a.phi_e < b.phi_e;
  };
  const std::vector<BranchStateSample> rows =
      record_samples(*turned_, [](double) { return true; });
  std::vector<BranchStateSample> turned = rows;
  std::sort(turned.begin(), turned.end(), by_phi);
  const std::vector<BranchStateSample> symmetric = symmetric_samples_by_phi();
  for (const BranchStateSample& s : turned) {
    const std::optional<double> reference = branch_energy_at(symmetric, s.phi_e);
    if (!reference) continue;
    const double below = (*reference - s.energy) / *reference;
    if (!t.largest_energy_below_symmetric || below > *t.largest_energy_below_symmetric) {
      t.largest_energy_below_symmetric = below;
      t.largest_energy_below_symmetric_phi = s.phi_e;
    }
  }
  if (!rows.empty()) {
    t.lowest_phi = turned.front().phi_e;
    t.highest_phi = turned.back().phi_e;
    // The highest sample, with its record row's S4 defect and gamma.
    const auto top = static_cast<std::size_t>(
        std::max_element(rows.begin(), rows.end(), by_phi) - rows.begin());
    if (const auto reference = branch_energy_at(symmetric, rows[top].phi_e))
      t.top_energy_relative = (rows[top].energy - *reference) / *reference;
    t.top_s4_defect = turned_->value(top, "s4_defect");
    t.top_gamma = turned_->value(top, "gamma");
  }
  // Its first loss of stability by increasing phi_e above its start: the special point between
  // the last stable and the first unstable sample (that sample if none was located). Below the
  // start the downward trace is stable down to its first special point, where it ends: the
  // sample just past that point (past a fold, on its unstable half) is no loss by increasing
  // phi_e.
  for (std::size_t k = 1; k < turned.size() && !t.phi_crit_stability; ++k) {
    if (turned[k - 1].phi_e < t.start_phi) continue;
    if (!(turned[k - 1].negative == 0 && turned[k].negative > 0)) continue;
    t.phi_crit_stability = turned[k].phi_e;
    for (const RecordedEvent& e : turned_->events())
      if (e.phi_e >= turned[k - 1].phi_e && e.phi_e <= turned[k].phi_e)
        t.phi_crit_stability = e.phi_e;
  }
  // phi_e^crit by energy is measured against the turned cone from here on: it is the lower of
  // the two (the mesh's mirror lines hold the symmetric one), and the continuum does not tell
  // the two orientations apart.
  results_.phi_crit_energy_reference = "turned";
  results_.phi_crit_energy.reset();
  results_.phi_crit_energy_criterion.clear();
  if (const auto exchange =
          ground_state_exchange(turned, skewed_samples(), {}, skewed_special_points())) {
    results_.phi_crit_energy = exchange->phi_e;
    results_.phi_crit_energy_criterion = exchange->criterion;
  }
  say("# turned branch: " +
      (t.largest_energy_below_symmetric
           ? "at most " + fixed(100.0 * *t.largest_energy_below_symmetric, 4) +
                 " % below the symmetric branch"
           : std::string("not compared with the symmetric branch")) +
      "; a stable skewed cone below it from " +
      (results_.phi_crit_energy ? fixed(*results_.phi_crit_energy, 6) : std::string("nowhere")));
  results_.turned = std::move(t);
}

/// Stage 6 (study.hard_contact_at): the saved state nearest each requested phi_e of each branch
/// of study.hard_contact_branches (the turned and the symmetric one by default), solved again
/// under Ipopt's hard constraints and compared with the penalty's
/// (studies/hard_contact_check.hpp); each check to BRANCH/hard_contact_phiP.json.
void EconeContactRun::check_hard_contact_points() {
  for (const double at : scene_.study.hard_contact_at) {
    for (const std::string& branch : scene_.study.hard_contact_branches) {
      const std::string branch_dir = dir_ + "/" + branch;
      if (!fs::exists(fs::path(branch_dir) / "states")) continue;  // the branch was not traced
      const std::optional<BranchSample> state =
          nearest_saved_state(branch_dir, at, model_->dimension(), fingerprint_);
      if (!state) continue;
      say("# stage 6: the " + branch + " branch at phi_e = " + fixed(state->parameter, 6) +
          " under Ipopt's hard contact constraints");
      EconeHardContactPoint p;
      p.branch = branch;
      p.at = at;
      std::ostringstream name;
      name << branch << "/hard_contact_phi" << std::setprecision(10) << at << ".json";
      p.file = name.str();
      const HardContactCheck* recorded =
          recorded_ ? recorded_->hard_contact_at(branch, at) : nullptr;
      if (recorded) {
        p.check = *recorded;
        say("#   taken from stages.json");
      } else {
        p.check = check_hard_contact(scene_, *model_, *proxy_, *state);
        ++cost_.hard_contact_checks;
        cost_.hard_contact_seconds += p.check.seconds;
      }
      write_file_atomically(dir_ + "/" + p.file, hard_contact_check_json(p.check));
      std::ostringstream line;
      line << "#   " << (p.check.converged ? "converged" : "not converged") << " ("
           << p.check.message << "), " << p.check.iterations << " iterations, "
           << fixed(p.check.seconds, 1) << " s; elastic energy hard - penalty "
           << std::setprecision(3) << -100.0 * p.check.relative_energy_difference
           << " %, S4 defect " << p.check.penalty_s4_defect << " -> " << p.check.hard_s4_defect
           << ", gamma " << p.check.penalty_gamma << " -> " << p.check.hard_gamma;
      say(line.str());
      p.check.x.resize(0);  // results.json keeps the comparison, not the state
      stages_.hard_contact.push_back({branch, at, p.check});
      if (!recorded) save_stages();
      results_.hard_contact.push_back(std::move(p));
    }
  }
}

/// Stage 7 (study.compare_modes): each n-fold cone traced without contact from the flat sheet
/// (a cone_branch study in DIR/cone_nN, resumed like stage 1), and its energy set against the
/// two-fold cone's at the same phi_e.
void EconeContactRun::trace_compared_modes() {
  const std::vector<BranchStateSample> two_fold = symmetric_samples_by_phi();
  for (const int n : scene_.study.compare_modes) {
    const Scene mode_scene = compared_mode_scene(scene_, n);
    const std::string name = fs::path(mode_scene.output.directory).filename().string();
    ConeBranchStudyOptions options = cone_branch_study_options(mode_scene);
    if (existing_ == ExistingOutput::Resume && fs::exists(fs::path(mode_scene.output.directory)))
      options.start = ConeBranchStart::LastState;
    else
      fs::remove_all(mode_scene.output.directory);
    say("# stage 7: the " + std::to_string(n) + "-fold cone without contact, into " +
        mode_scene.output.directory);
    const ConeBranchStudy cone =
        run_cone_branch_study(mode_scene, options, mode_scene.output.directory, progress_);
    EconeComparedMode m;
    m.mode = n;
    m.directory = name;
    m.phi_branch = cone.results.phi_branch;
    m.phi_max = cone.results.phi_max;
    m.eb_hat_max = cone.results.eb_hat_max;
    m.phi_first_contact = cone.results.phi_gap_h;
    m.highest_phi = cone.results.phi_highest;
    m.completed = cone.results.completed;
    m.end = cone.results.end;
    if (!m.completed) {
      const std::string why = "the " + std::to_string(n) + "-fold cone: " + m.end;
      mark_incomplete(why);
    }
    const double inf = std::numeric_limits<double>::infinity();
    for (const BranchEnergySample& s :
         saved_energies(mode_scene.output.directory, m.phi_branch.value_or(inf), inf)) {
      const std::optional<double> reference = branch_energy_at(two_fold, s.parameter);
      if (!reference || !(*reference > 0.0)) continue;
      const double above = (s.energy - *reference) / *reference;
      if (!m.lowest_energy_above_two_fold || above < *m.lowest_energy_above_two_fold) {
        m.lowest_energy_above_two_fold = above;
        m.lowest_energy_above_two_fold_phi = s.parameter;
      }
    }
    say("# the " + std::to_string(n) + "-fold cone: " + m.end + "; " +
        (m.lowest_energy_above_two_fold
             ? "at least " + fixed(100.0 * *m.lowest_energy_above_two_fold, 3) +
                   " % above the two-fold cone (at phi_e = " +
                   fixed(*m.lowest_energy_above_two_fold_phi, 4) + ")"
             : std::string("not compared with the two-fold cone")));
    results_.compared_modes.push_back(std::move(m));
  }
}

/// Stage 8 (study.wind_to): from the highest stable state that breaks S4 (of the skewed or the
/// turned cone), the sheet grown on in
/// natural steps, each a strict minimum of shell + penalty (solvers/contact/
/// contact_growth_path.hpp), so that where a stable state ends it drops onto the next one: the
/// wound-up cones. Every accepted state to DIR/wound (row, state), the shapes at
/// study.wind_shapes_at and at the end as VTU.
void EconeContactRun::wind_up() {
  if (!scene_.study.wind_to) {
    fs::remove_all(fs::path(dir_) / "wound");  // a stale winding of an earlier scene
    return;
  }
  const double target = *scene_.study.wind_to;
  // The start: the skewed cone's top, or the turned cone's (its core skews too, and where the
  // skewed search found no state it is the only cone that breaks S4): the higher of the two,
  // and the lower in energy where both reach the same phi_e (within a step).
  const bool skewed = top_skewed_.x.size() > 0, turned = top_turned_.x.size() > 0;
  if (!skewed && !turned) {
    fs::remove_all(fs::path(dir_) / "wound");  // a stale winding of an earlier run
    const std::string why =
        "no winding: neither the skewed nor the turned branch has a stable sample that breaks S4";
    say("# stage 8: " + why);
    mark_incomplete(why);
    return;
  }
  // Energies at two tops a little apart in phi_e are compared each against the symmetric
  // branch at its own phi_e (E rises with phi_e by more than the two cones differ).
  const std::vector<BranchStateSample> symmetric = symmetric_samples_by_phi();
  const auto relative = [&symmetric](const TopSample& top) {
    const std::optional<double> reference = branch_energy_at(symmetric, top.phi);
    return reference && *reference > 0.0 ? top.energy / *reference : top.energy;
  };
  bool from_turned = !skewed;
  if (skewed && turned)
    from_turned = std::abs(top_turned_.phi - top_skewed_.phi) <= scene_.study.contact_max_step
                      ? relative(top_turned_) < relative(top_skewed_)
                      : top_turned_.phi > top_skewed_.phi;
  const TopSample& start = from_turned ? top_turned_ : top_skewed_;
  const auto started = std::chrono::steady_clock::now();
  EconeWindUp w;
  w.start_branch = from_turned ? "turned" : "skewed";
  w.start_phi = start.phi;
  w.target = target;
  // A resumed study continues the winding it recorded from the same start (the stages before
  // are deterministic and give it again, to the bit) from its last committed state, with the
  // step and pins the path had there (below).
  const std::string wound_dir = dir_ + "/wound";
  const std::string start_file = wound_dir + "/start.state";
  const std::string pins_file = wound_dir + "/pins.txt";
  bool resumed = false;
  if (existing_ == ExistingOutput::Resume && BranchRecord::exists(wound_dir) &&
      fs::exists(start_file) && fs::exists(pins_file) &&
      !BranchRecord::committed_last_state(wound_dir).empty()) {
    const BranchSample recorded = load_branch_state(start_file, model_->dimension(), fingerprint_);
    resumed = recorded.parameter == start.phi && recorded.x == start.x;
    if (!resumed)
      say("# stage 8: the recorded winding started from another state; it is traced afresh");
  }
  if (resumed) {
    wound_ = std::make_unique<BranchRecord>(wound_dir, kContactStudyColumns,
                                            BranchRecord::Start::Continue);
  } else {
    fs::remove_all(wound_dir);  // stale once the branches are traced again
    wound_ =
        std::make_unique<BranchRecord>(wound_dir, kContactStudyColumns, BranchRecord::Start::Fresh);
    BranchSample s;
    s.x = start.x;
    s.parameter = start.phi;
    s.tangent_state = Eigen::VectorXd::Zero(start.x.size());
    save_branch_state(start_file, s, fingerprint_);
  }
  say("# stage 8: the sheet grown on from the " + w.start_branch +
      " cone's highest stable state at phi_e = " + fixed(start.phi, 6) + " to " +
      fixed(target, 6) + ", a minimum at every step" +
      (resumed ? " (resumed from its record, " + std::to_string(wound_->rows()) + " states)" : ""));
  ContactGrowthOptions growth = econe_winding_options(scene_, *model_, *proxy_);
  std::vector<double> stops = scene_.study.wind_shapes_at;
  stops.push_back(target);
  std::sort(stops.begin(), stops.end());
  stops.erase(std::unique(stops.begin(), stops.end()), stops.end());
  const auto on_point = [&](const ContactGrowthPoint& p) {
    // The pins the path goes on from, before the state is committed: a resumed path takes the
    // pins of its last committed state or of the one after it, which give the same next pins.
    std::string pins_text;
    for (const Eigen::Index dof : p.pins) pins_text += std::to_string(dof) + "\n";
    write_file_atomically(pins_file, pins_text);
    if (p.jumped) {
      w.jumps.push_back(p.sample.sample.parameter);
      std::ostringstream j;
      j << std::setprecision(10) << "{\"kind\": \"jump\", \"phi_e\": " << p.sample.sample.parameter
        << ", \"saddle_escapes\": " << p.saddle_escapes << "}";
      wound_->add_event(j.str(), {"jump", p.sample.sample.parameter, "wound", {}});
      say("# wound: the stable state ended; the sheet dropped onto another one at phi_e = " +
          fixed(p.sample.sample.parameter, 6));
    }
    record_sample("wound", *wound_, p.sample);
    const ContactStepWork& k = p.work;
    EconeWindingWork& spent = cost_.winding ? *cost_.winding : cost_.winding.emplace();
    ++spent.steps;
    spent.minimisations += k.tries;
    spent.newton_iterations += k.newton_iterations;
    spent.factorizations += k.factorizations;
    spent.eigen_solves += k.eigen_solves;
    say("#   its cost: " + std::to_string(k.tries) + " minimisations (" +
        (p.from_prediction          ? "from the prediction"
         : k.prediction_discarded ? "prediction discarded"
                                  : "no prediction") +
        "), " + std::to_string(k.halvings) + " halvings, " + std::to_string(k.solves) +
        " Newton solves, " + std::to_string(k.newton_iterations) + " iterations, " +
        std::to_string(k.factorizations) + " factorisations, " + std::to_string(k.eigen_solves) +
        " eigensolves");
  };
  // The path carries its state, step and pins from one point to the next, across the stops and
  // across a resume (the last committed state with its next step, and pins.txt).
  std::vector<Eigen::Index> pins = rigid_pins_for_state(*model_, start.x, pinned_, growth.contact);
  Eigen::VectorXd x = start.x;
  double phi = start.phi;
  // The accepted state before x, from which the path's secant predictor extrapolates: none at
  // the start; on a resume the committed state before the last one (or the start).
  BranchSample before;
  w.highest_phi = phi;
  if (resumed) {
    const BranchSample last = load_branch_state(wound_dir + "/" + wound_->last_state(),
                                                model_->dimension(), fingerprint_);
    const std::vector<fs::path> saved = saved_state_files(wound_dir);
    before = saved.size() >= 2
                 ? load_branch_state(saved[saved.size() - 2].string(), model_->dimension(),
                                     fingerprint_)
                 : load_branch_state(start_file, model_->dimension(), fingerprint_);
    x = last.x;
    phi = last.parameter;
    if (last.next_step > 0.0 && last.next_step <= growth.max_step)
      growth.initial_step = last.next_step;
    pins = read_winding_pins(pins_file, model_->dimension());
    w.steps = static_cast<int>(wound_->rows());
    w.highest_phi = phi;
    for (const RecordedEvent& e : wound_->events())
      if (e.kind == "jump") w.jumps.push_back(e.phi_e);
  }
  // The path ends a growth at its target to rounding (a sum of steps): within this it is there.
  const double at_stop = 1e-9;
  std::string message;
  for (const double stop : stops) {
    if (stop > phi + at_stop) {
      const ContactGrowthResult g = grow_with_contact(*model_, *proxy_, x, phi, stop, pins, growth,
                                                      on_point, before.x.size() ? &before : nullptr);
      w.steps += g.steps;
      w.failed_steps += g.failed_steps;
      w.predicted_steps += g.predicted_steps;
      w.discarded_predictions += g.discarded_predictions;
      if (g.steps > 0) {
        before = g.before_last;
        x = g.last.sample.sample.x;
        phi = g.last.sample.sample.parameter;
        pins = g.last.pins;
        growth.initial_step = g.last.sample.sample.next_step;
        w.highest_phi = phi;
      }
      if (!g.reached_target) {
        message = g.message;
        break;
      }
    }
    // The shape where the path stopped (on the stop, to rounding): the shell with
    // its energy densities, and the contact proxy with its pair forces. A resumed path keeps
    // the shapes its record committed.
    std::ostringstream name;
    name << "shape_phi" << std::setprecision(10) << stop;
    const std::string shell = name.str() + ".vtu", contact = name.str() + "_contact.vtu";
    const bool written = fs::exists(fs::path(wound_dir) / shell) &&
                         fs::exists(fs::path(wound_dir) / contact);
    if (stop < phi - at_stop && !written) continue;  // passed before this key asked for it
    if (!written) {
      BranchSample at;
      at.x = x;
      at.parameter = phi;
      const ContactBranchSample s = describe_contact_sample(
          *model_, *proxy_, at, near_penalty_pairs(*proxy_, x, growth.contact), growth.contact);
      wound_->add_snapshot(phi, shell, shell_snapshot(*model_, x, phi, 2));
      const ContactGapConstraints gaps(*proxy_, s.pairs, growth.contact.contact_distance,
                                       model_->dimension(), growth.contact.gap);
      wound_->write_surface(contact, contact_snapshot(*proxy_, gaps, x, s.forces));
      wound_->commit();
      say("# wound: wrote the shape at phi_e = " + fixed(phi, 6) + " (wound/" + shell +
          ", _contact.vtu)");
    }
    w.shapes.push_back({stop, "wound/" + shell, "wound/" + contact});
  }
  w.reached = message.empty() && phi >= target - at_stop;
  w.end = w.reached ? "reached phi_e = " + fixed(target, 6) : message;
  w.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  say("# stage 8: " + w.end + " (" + std::to_string(w.steps) + " steps, " +
      std::to_string(w.failed_steps) + " failed, " + std::to_string(w.jumps.size()) +
      " jumps; this run's steps " + std::to_string(w.predicted_steps) + " from the predictor, " +
      std::to_string(w.discarded_predictions) + " predictions discarded)");
  if (!w.reached) {
    const std::string why = "winding: " + w.end;
    mark_incomplete(why);
  }
  results_.wound = std::move(w);
}

/// f = E_s / E_b at the highest sample of each branch traced with contact (results.json's
/// energy_ratio_f).
void EconeContactRun::measure_energy_ratios() {
  results_.energy_ratio_f.clear();
  const std::pair<const char*, const BranchRecord*> branches[] = {{"symmetric", symmetric_.get()},
                                                                  {"skewed", skewed_.get()},
                                                                  {"turned", turned_.get()},
                                                                  {"wound", wound_.get()}};
  for (const auto& [name, record] : branches) {
    if (!record || record->rows() == 0) continue;
    std::size_t top = 0;
    for (std::size_t k = 1; k < record->rows(); ++k)
      if (record->value(k, "phi_e") > record->value(top, "phi_e")) top = k;
    results_.energy_ratio_f.push_back(
        {name, record->value(top, "phi_e"),
         record->value(top, "E_stretch") / record->value(top, "E_bend")});
  }
}

EconeContactResults EconeContactRun::run() {
  const auto started = std::chrono::steady_clock::now();
  fs::create_directories(dir_);
  if (existing_ != ExistingOutput::Resume) fs::remove(fs::path(dir_) / "results.json");
  write_file_atomically(dir_ + "/scene.json", scene_to_json(scene_));
  trace_cone();
  // Stale once the branches are traced again; contact_cost.json is this run's, written at its end.
  fs::remove(fs::path(dir_) / "results.json");
  fs::remove(fs::path(dir_) / "contact_cost.json");
  set_up_contact();
  fs::remove_all(fs::path(dir_) / "orientation");  // stale once the cone is traced again
  check_orientation();
  // What the stages after the cone found, from a resumed study's record of the same scene
  // and start (studies/econe_stage_record.hpp); this run's record starts from the key alone.
  stages_.key = econe_stage_key(scene_, start_);
  if (recorded_ && recorded_->key != stages_.key) {
    say("# stages.json was recorded from another scene or another start of the contact era: "
        "stages 2-6 are traced afresh");
    recorded_.reset();
  }
  const EconeBranchResult traced = contact_branches();
  summarize(traced);
  trace_turned();
  check_hard_contact_points();
  trace_compared_modes();
  wind_up();
  measure_energy_ratios();
  report_phase_forces();

  EconeContactResults& r = results_;
  r.thickness = h_;
  r.mesh.family = mesh_family_name(scene_.mesh.family);
  if (graded_by_size(scene_.mesh.family)) r.mesh.size_slope = scene_.mesh.size_slope;
  r.mesh.elements = static_cast<long long>(model_->num_elements());
  r.mesh.unknowns = static_cast<long long>(model_->dimension());
  r.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  write_file_atomically(dir_ + "/results.json", econe_contact_results_json(r));
  cost_.wall_seconds = r.wall_seconds;
  if (cost_.winding && results_.wound) cost_.winding->seconds = results_.wound->seconds;
  write_file_atomically(dir_ + "/contact_cost.json", econe_contact_cost_json(cost_));
  const EconeTraceWork spent = all_traces(cost_);
  if (spent.steps > 0) {
    const TraceCost& c = spent.cost.continuation;
    say("# the traces with contact: " + std::to_string(spent.steps) + " steps, " +
        std::to_string(c.factorizations) + " factorisations (" +
        fixed(static_cast<double>(c.factorizations) / spent.steps, 2) + " per step), " +
        std::to_string(c.stability_evaluations) + " stability indices; wrote " + dir_ +
        "/contact_cost.json");
  }
  const auto show = [](const std::optional<double>& v) {
    return v ? fixed(*v, 6) : std::string("none");
  };
  say("# first contact " + show(r.phi_first_contact) + ", stability lost " +
      show(r.phi_crit_stability) + ", energy crossing " + show(r.phi_crit_energy) + "; " + r.end);
  say("# wrote " + dir_ + "/results.json");
  return r;
}

}  // namespace

Scene econe_contact_cone_scene(const Scene& scene) {
  Scene cone = scene;
  cone.study.kind = StudyKind::ConeBranch;
  // The contact era's, not the contact-free cone's.
  cone.study.hard_contact_at.clear();
  cone.study.hard_contact_branches = default_scene().study.hard_contact_branches;
  cone.study.wind_to.reset();
  cone.study.wind_shapes_at.clear();
  cone.study.compare_modes.clear();
  cone.study.through_contact = false;
  cone.output.directory = (fs::path(scene.output.directory) / kConeDir).string();
  return cone;
}

std::string econe_contact_record_file() {
  // Appended rather than operator+ on a temporary, on which GCC 12 warns (-Warray-bounds).
  std::string path = kConeDir;
  path.append("/record.json");
  return path;
}

void check_econe_contact_directory(const std::string& directory, ExistingOutput existing) {
  check_output_directory(directory, existing, "study", econe_contact_record_file());
}

EconeContactResults run_econe_contact_study(const Scene& scene, ExistingOutput existing,
                                            const StudyProgress& progress) {
  EconeContactRun run(scene, existing, progress);
  return run.run();
}

}  // namespace growshell
