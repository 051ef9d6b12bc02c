#pragma once
/// \file
/// The two e-cone branches past first contact and the critical excess angle between them: the
/// symmetric branch followed through contact (also where it is unstable), the skewed branch
/// found by relaxing a perturbed symmetric state (or entered at the symmetric branch's loss of
/// stability) and followed down to where it ends and up, and phi_e^crit both ways (energy
/// crossing, stability loss). Built on trace_contact_branch (contact_branch.hpp); see
/// docs/contact.md.

#include <Eigen/Core>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "libshell/assembly/shell_model.hpp"
#include "libshell/contact/contact_proxy.hpp"
#include "solvers/contact/contact_branch.hpp"
#include "solvers/contact/contact_equilibrium.hpp"
#include "solvers/continuation/branch_crossing.hpp"

namespace growshell {

/// Which branch a sample or special point belongs to.
enum class EconeBranch { Symmetric, Skewed };

/// "symmetric" or "skewed".
const char* to_string(EconeBranch branch);

/// Where the skewed branch is looked for.
enum class SkewedStart {
  /// Relax the last symmetric state pushed along its lowest mode (the recipe: from
  /// phi_e = 10 back down).
  Top,
  /// Enter the branch born at the symmetric branch's first stability loss along its critical
  /// mode (falls back to Top if there is no such branch point).
  BranchPoint,
};

/// Settings of trace_econe_branches.
struct EconeBranchOptions {
  /// Distances, stiffness, pair selection and step control of every trace (parameter bounds
  /// and max_steps are set per branch from the fields below). Its symmetric_subspace, if set,
  /// applies to the symmetric branch only.
  ContactBranchOptions contact;
  double symmetric_end = 10.0;  ///< the symmetric branch is followed up to this phi_e
  /// The skewed branch is followed up to this phi_e (e.g. beyond 4 pi).
  double skewed_end = 10.0;
  /// The skewed branch is followed down to this phi_e at most (NaN: phi_start - 1). Its
  /// lower end can lie well below the start: at h = 0.04 the skewed cone exists without
  /// contact a whole radian below first contact.
  double skewed_min = std::numeric_limits<double>::quiet_NaN();
  int max_steps_per_branch = 600;
  /// The downward skewed trace ends where phi_e turns back (turning_back_event): at the fold
  /// where the skewed cone, going down, ends. Next to that fold the corrector can converge onto
  /// another branch (a snap the trace would then follow under the skewed cone's name), and the
  /// unstable part beyond it is not needed for phi_e^crit. false (default): down to
  /// skewed_min, round the fold and back up to the start's phi_e. (Not at its first special
  /// point: on the paper's scene the skewed cone's index flips on a small margin at 6.27 in
  /// some runs, above its crossing with the symmetric branch.)
  bool skewed_down_ends_at_fold = false;
  /// With skewed_down_ends_at_fold: the downward trace also ends once its fold, extrapolated
  /// from its last two samples, lies this close in phi_e after a failed step
  /// (ArclengthOptions::fold_approach_tolerance; 0: only at min_step).
  double skewed_fold_approach_tolerance = 0.0;
  /// If set, the skewed branch's traces take only the steps it accepts
  /// (ArclengthOptions::accept_step): e.g. no step that lands on a state keeping S4, the
  /// symmetric cone the corrector can snap onto next to the skewed cone's fold.
  std::function<bool(const BranchSample& from, const BranchSample& to)> skewed_accept_step;
  /// If set (e.g. half_turn_subspace), the skewed branch is traced in it from a relaxed state
  /// that has its symmetry to a tenth of the contact distance in some frame; from one that
  /// has not, in the full space, with a note. The stability index stays the full Hessian's.
  std::shared_ptr<const SymmetricSubspace> skewed_subspace;
  /// If set, the skewed branch's traces in the full space hold the phase condition this returns
  /// for their start state (ContactBranchOptions::phase_functional), e.g. the fold pattern's
  /// orientation: on a mesh without the cone's mirrors the pattern's turn is nearly free once
  /// few pairs hold it. Not applied where the skewed branch is traced in skewed_subspace.
  std::function<Eigen::VectorXd(const Eigen::VectorXd& start)> skewed_phase_functional;
  bool trace_skewed = true;  ///< false: the symmetric branch only
  SkewedStart skewed_start = SkewedStart::Top;
  /// Top: the symmetric state pushed and relaxed is the first sample at or beyond this phi_e
  /// (NaN: the branch's last sample). Just past the stability loss the skewed state is a
  /// short slide away; from the symmetric state at 10 (h = 0.02, six negative modes) it is a
  /// winding of the sheet, and no unbounded Newton relaxation reached it in 400 iterations.
  double skew_search_at = std::numeric_limits<double>::quiet_NaN();
  /// Push along the lowest mode, in units of the contact distance at the mode's largest entry
  /// (small enough that no layer is pushed through another).
  double push = 0.5;
  /// A relaxed state counts as a different (skewed) state only if its energy is lower than
  /// the symmetric one by this fraction; the lowest of those is traced, however close the
  /// others (lowest_skewed_state.hpp).
  double energy_margin = 1e-4;
  /// If set, a relaxed state counts as skewed only if this accepts it, and the reason it gives
  /// otherwise goes to skewed_message. E.g. the cone studies reject a state that keeps the
  /// cone's S4 symmetry: the symmetric cone turned about its axis, which a mesh makes slightly
  /// cheaper than the traced one once contact pairs differ (on gmsh_d4 at h = 0.04, 0.19 %
  /// below it at phi_e = 7.2).
  std::function<bool(const Eigen::VectorXd& x, std::string& why_not)> accept_skewed;
  /// Where the searched state has the mirrors of contact.symmetric_subspace, push a mode that
  /// lies (without its rigid motion, to at least 0.99 of its squared norm) in a class odd
  /// under a mirror one way only: the other push starts next to the first's mirror image.
  /// Off by default: the relaxations land on one of several nearby skewed minima, and which
  /// one depends on the push to a few per cent, so the left-out push can be the one that
  /// finds the lowest (measured at h = 0.02: with it, a state 8.5e-5 above the skewed cone
  /// that both pushes find, whose branch ends at once; docs/performance.md, session 37).
  bool one_push_per_mirror_pair = false;
  /// Newton settings of the relaxation (minimisation of shell + penalty at fixed phi_e).
  NewtonOptions relaxation;
  /// Crossings closer than this to the branch point the skewed branch was entered at are the
  /// tangency of a pitchfork, not a crossing, and are dropped (radians).
  double tangency_exclusion = 1e-3;
  /// Crossings whose slope difference is below this fraction of the branches' slopes are
  /// dropped: there the skewed trace has come back onto the symmetric branch (through the
  /// subcritical branch point) and both interpolate the same energies (measured: 1e-5 of the
  /// slope at h = 0.04, against 1 for the true crossing).
  double coincidence_slope_ratio = 1e-3;
  /// If set, the relaxed skewed state (a minimum) is solved again with Ipopt under the hard
  /// constraints gap >= contact distance, from the penalty state, and compared
  /// (EconeBranchResult::ipopt_*).
  std::optional<ContactSolveOptions> verify_with_ipopt;
  /// The symmetric branch below the start (e.g. the contact-free cone traced up to x0), by
  /// increasing phi_e, with energies E_s + E_b (no contact there) and slopes: joined in front
  /// of the traced symmetric branch for the energy crossing (join_branch_samples), so that a
  /// skewed branch reaching below the start still finds its crossing. Empty: the traced
  /// branch only.
  std::vector<BranchEnergySample> symmetric_before;
};

/// Outcome of trace_econe_branches. Traces keep their last sample and message even when they
/// end early, so nothing computed is lost.
struct EconeBranchResult {
  ContactBranchTrace symmetric;
  ContactBranchTrace skewed_down;  ///< from the relaxed state downwards (Top)
  ContactBranchTrace skewed_up;    ///< from the relaxed state upwards, or from the branch point
  std::optional<LocatedEvent> first_contact;  ///< gap = contact distance on the symmetric branch
  /// First change of the symmetric branch's negative count from 0: phi_e^crit by stability.
  std::optional<SpecialPoint> stability_loss;
  bool skewed_found = false;
  std::string skewed_message;  ///< how the skewed branch was found, or why not
  double skewed_relaxed_energy = 0.0;    ///< J, at the relaxed skewed state (Top)
  double symmetric_top_energy = 0.0;     ///< J, the symmetric state it was compared with
  double skew_search_parameter = 0.0;    ///< phi_e of that state (Top)
  /// Energy crossings of the two branches (E_s + E_b + P), by parameter: phi_e^crit by energy.
  /// A crossing met by both skewed traces (within 1e-5) is listed once.
  std::vector<EnergyCrossing> crossings;
  /// Per crossing: the skewed samples on both sides of it are stable (negative count 0). A
  /// skewed trace that runs on past the branch's folds crosses the symmetric branch on its
  /// unstable parts too; the exchange of ground states is the first crossing flagged here.
  std::vector<bool> crossing_skewed_stable;
  double skewed_search_seconds = 0.0;
  /// Pushes of the search relaxed, and pushes left out by one_push_per_mirror_pair (the start
  /// has the mirrors of the symmetric subspace and the mode is odd under one of them: the push
  /// starts next to the image of the opposite one, already relaxed).
  int skewed_pushes_relaxed = 0;
  int skewed_pushes_skipped_as_images = 0;
  /// The Ipopt check of the relaxed skewed state (EconeBranchOptions::verify_with_ipopt).
  bool ipopt_checked = false;
  bool ipopt_converged = false;
  std::string ipopt_message;
  double ipopt_energy = 0.0;            ///< E_s + E_b at Ipopt's solution (J)
  double penalty_elastic_energy = 0.0;  ///< E_s + E_b at the penalty state (J)
  double ipopt_state_difference = 0.0;  ///< max |x_ipopt - x_penalty| (m)
  double ipopt_min_distance = 0.0;      ///< smallest pair distance at Ipopt's solution (m)
  double ipopt_seconds = 0.0;
};

/// Callbacks of trace_econe_branches (all optional), called as results arrive.
struct EconeBranchCallbacks {
  std::function<void(EconeBranch, const ContactBranchSample&)> on_sample;
  std::function<void(EconeBranch, const SpecialPoint&)> on_special;
  std::function<void(const LocatedEvent&)> on_event;  ///< first contact
  std::function<void(const std::string&)> on_note;    ///< progress notes for a log
};

/// From the equilibrium (x0, phi0) of `model` below first contact (e.g. the n = 2 cone grown
/// without contact), with `fixed_dofs` held: traces the symmetric branch up to
/// options.symmetric_end, finds and traces the skewed branch, and locates the energy crossing.
/// Throws std::invalid_argument for bad options (naming the field).
EconeBranchResult trace_econe_branches(const ShellModel& model, const ContactProxy& proxy,
                                       const Eigen::Ref<const Eigen::VectorXd>& x0, double phi0,
                                       const std::vector<Eigen::Index>& fixed_dofs,
                                       const EconeBranchOptions& options,
                                       const EconeBranchCallbacks& callbacks = {});

}  // namespace growshell
