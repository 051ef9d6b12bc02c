#include "solvers/contact/econe_branches.hpp"

#include "core/objective_at_parameter.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "libshell/analysis/self_intersection.hpp"
#include "libshell/contact/contact_penalty.hpp"
#include "libshell/contact/near_contact_pairs.hpp"
#include "libshell/mesh/rigid_motion.hpp"
#include "solvers/contact/contact_equilibrium.hpp"
#include "solvers/contact/contact_growth_path.hpp"
#include "solvers/contact/lowest_skewed_state.hpp"
#include "solvers/contact/penalty_warm_start.hpp"
#include "solvers/continuation/symmetric_subspace.hpp"
#include "solvers/continuation/turning_back_event.hpp"
#include "solvers/newton/newton_solver.hpp"
#include "solvers/stability/lowest_eigenpairs.hpp"
#include "solvers/stability/mode_symmetry_class.hpp"

namespace growshell {

const char* to_string(EconeBranch branch) {
  return branch == EconeBranch::Symmetric ? "symmetric" : "skewed";
}

namespace {

using Clock = std::chrono::steady_clock;

/// A start is taken to have the mirrors when its asymmetry is below this fraction of its
/// extent (a state traced in the subspace has none, up to rounding).
constexpr double kMirrorImageAsymmetry = 1e-9;
/// A mode is pushed one way only when its part in a class odd under a mirror holds this
/// fraction of its squared norm, without its rigid motion, or more: the other push then
/// starts within 2 sqrt(1 - 0.99) = 0.2 of the push from the first's mirror image. (Pushing
/// along that part instead, exactly one image of the other, changes which state the
/// relaxation finds: at h = 0.02 a skewed state 8.5e-5 higher, whose branch ends at once.)
constexpr double kMirrorClassModeWeight = 0.99;

/// The `count` eigenpairs of the penalised Hessian at (y, phi) nearest zero (nearest_zero) or
/// lowest.
Eigenpairs modes_at(const ShellModel& model, const ContactProxy& proxy, const Eigen::VectorXd& y,
                    double phi, const std::vector<Eigen::Index>& fixed,
                    const ContactBranchOptions& o, bool nearest_zero, int count) {
  PenalizedShell near(model, proxy, near_penalty_pairs(proxy, y, o), o);
  EigenpairOptions eig;
  eig.count = count;
  if (nearest_zero) eig.shift = 0.0;
  ObjectiveAtParameter near_at(near.energy, phi);
  return lowest_eigenpairs(near_at, y, fixed, eig);
}

void validate(const EconeBranchOptions& o) {
  if (!(o.push > 0.0 && std::isfinite(o.push)))
    throw std::invalid_argument("EconeBranchOptions::push must be finite and > 0");
  if (!(o.energy_margin >= 0.0 && std::isfinite(o.energy_margin)))
    throw std::invalid_argument("EconeBranchOptions::energy_margin must be finite and >= 0");
  if (o.max_steps_per_branch < 1)
    throw std::invalid_argument("EconeBranchOptions::max_steps_per_branch must be >= 1");
  if (!(o.skewed_fold_approach_tolerance >= 0.0))
    throw std::invalid_argument("EconeBranchOptions::skewed_fold_approach_tolerance must be >= 0");
  if (!(o.tangency_exclusion >= 0.0))
    throw std::invalid_argument("EconeBranchOptions::tangency_exclusion must be >= 0");
  if (!(o.coincidence_slope_ratio >= 0.0 && o.coincidence_slope_ratio < 1.0))
    throw std::invalid_argument("EconeBranchOptions::coincidence_slope_ratio must be in [0, 1)");
  try {
    join_branch_samples(o.symmetric_before, {});
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("EconeBranchOptions::symmetric_before: ") + e.what());
  }
}

}  // namespace

EconeBranchResult trace_econe_branches(const ShellModel& model, const ContactProxy& proxy,
                                       const Eigen::Ref<const Eigen::VectorXd>& x0, double phi0,
                                       const std::vector<Eigen::Index>& fixed_dofs,
                                       const EconeBranchOptions& options,
                                       const EconeBranchCallbacks& callbacks) {
  validate(options);
  if (!(options.symmetric_end > phi0))
    throw std::invalid_argument("EconeBranchOptions::symmetric_end must exceed the start phi_e");
  const ContactBranchOptions& o = options.contact;
  // Rigid-motion pins for the states the search starts from.
  const auto pins_at = [&](const Eigen::VectorXd& x) {
    return rigid_pins_for_state(model, x, fixed_dofs, o);
  };
  const double h_c = o.contact_distance;
  const auto note = [&](const std::string& text) {
    if (callbacks.on_note) callbacks.on_note(text);
  };
  EconeBranchResult out;

  // The symmetric branch, with the first-contact event (smallest pair distance = h_c; its
  // test function needs a pair search, so it is evaluated only until the event is found).
  bool contact_found = false;
  BranchEvent contact_event;
  contact_event.kind = "contact";
  contact_event.value = [&](const BranchSample& s) {
    if (contact_found) return -h_c;
    const ContactCandidates near =
        near_contact_pairs(proxy, s.x, 2.0 * h_c, o.exclusion_radius, o.selection);
    if (near.empty()) return h_c;
    return std::min(2.0 * h_c, smallest_pair_distance(proxy, near, s.x)) - h_c;
  };
  std::vector<BranchEnergySample> symmetric_energy, down_energy, up_energy;
  const auto energy_of = [](const ContactBranchSample& s) {
    return BranchEnergySample{s.sample.parameter,
                              s.stretching_energy + s.bending_energy + s.penalty_energy,
                              s.energy_slope};
  };
  BranchSample search_start;  // Top: the sample the skewed search starts from
  ContactBranchOptions symmetric_options = o;
  symmetric_options.arclength.parameter_min = phi0 - 1.0;
  symmetric_options.arclength.parameter_max = options.symmetric_end;
  symmetric_options.arclength.max_steps = options.max_steps_per_branch;
  out.symmetric = trace_contact_branch(
      model, proxy, x0, phi0, Eigen::VectorXd::Zero(model.dimension()), 1.0, fixed_dofs,
      symmetric_options,
      [&](const ContactBranchSample& s) {
        symmetric_energy.push_back(energy_of(s));
        if (search_start.x.size() == 0 && s.sample.parameter >= options.skew_search_at)
          search_start = s.sample;
        if (callbacks.on_sample) callbacks.on_sample(EconeBranch::Symmetric, s);
      },
      [&](const SpecialPoint& sp) {
        if (!out.stability_loss && sp.negative_before == 0 && sp.negative_after > 0)
          out.stability_loss = sp;
        if (callbacks.on_special) callbacks.on_special(EconeBranch::Symmetric, sp);
      },
      {contact_event},
      [&](const LocatedEvent& e) {
        if (e.kind == "contact") {
          contact_found = true;
          if (!out.first_contact) out.first_contact = e;
        }
        if (callbacks.on_event) callbacks.on_event(e);
      });
  note("symmetric branch: " + out.symmetric.message + " (" + std::to_string(out.symmetric.steps) +
       " steps)");

  // The skewed branch.
  const auto t_search = Clock::now();
  // Negative counts of the skewed samples, parallel to down_energy / up_energy.
  std::vector<int> down_negative, up_negative;
  const auto on_skewed_sample = [&](std::vector<BranchEnergySample>& energies,
                                    std::vector<int>& negative) {
    return [&](const ContactBranchSample& s) {
      energies.push_back(energy_of(s));
      negative.push_back(s.sample.negative_eigenvalues);
      if (callbacks.on_sample) callbacks.on_sample(EconeBranch::Skewed, s);
    };
  };
  const auto on_skewed_special = [&](const SpecialPoint& sp) {
    if (callbacks.on_special) callbacks.on_special(EconeBranch::Skewed, sp);
  };
  ContactBranchOptions skewed_options = o;
  skewed_options.symmetric_subspace = nullptr;  // the skewed branch breaks the symmetry
  skewed_options.arclength.parameter_min =
      std::isnan(options.skewed_min) ? phi0 - 1.0 : options.skewed_min;
  skewed_options.arclength.parameter_max = options.skewed_end;
  skewed_options.arclength.max_steps = options.max_steps_per_branch;
  if (options.skewed_accept_step) skewed_options.arclength.accept_step = options.skewed_accept_step;
  std::optional<double> entered_at;  // branch point the skewed branch was entered at
  if (!options.trace_skewed) {
    out.skewed_message = "not traced (trace_skewed = false)";
  } else if (out.symmetric.last.sample.x.size() != model.dimension()) {
    out.skewed_message = "not searched: the symmetric branch has no converged sample";
  } else if (options.skewed_start == SkewedStart::BranchPoint && out.stability_loss &&
             out.stability_loss->kind == SpecialPoint::Kind::BranchPoint) {
    const SpecialPoint& bp = *out.stability_loss;
    const std::vector<Eigen::Index> pins = pins_at(bp.x);
    const Eigenpairs critical = modes_at(model, proxy, bp.x, bp.parameter, pins, o, true, 1);
    const double lambda = critical.values[0];
    const Eigen::VectorXd mode = critical.vectors.col(0);
    out.skewed_search_seconds = std::chrono::duration<double>(Clock::now() - t_search).count();
    std::ostringstream m;
    m << "entered at the branch point phi_e = " << bp.parameter
      << " along the critical mode (eigenvalue " << lambda << ")";
    out.skewed_message = m.str();
    note(out.skewed_message);
    out.skewed_found = true;
    entered_at = bp.parameter;
    // Off the branch point by h_c / 4 at the mode's largest entry: far enough for the corrector
    // to stay off the symmetric branch, close enough to land on the bifurcating one.
    const double offset = 0.25 * h_c / mode.cwiseAbs().maxCoeff();
    if (options.skewed_phase_functional)
      skewed_options.phase_functional = options.skewed_phase_functional(bp.x + offset * mode);
    out.skewed_up = trace_contact_branch(
        model, proxy, bp.x + offset * mode, bp.parameter, mode, 0.0, pins, skewed_options,
        on_skewed_sample(up_energy, up_negative), on_skewed_special);
  } else {
    const BranchSample top = search_start.x.size() > 0 ? search_start : out.symmetric.last.sample;
    out.skew_search_parameter = top.parameter;
    const std::vector<Eigen::Index> pins = pins_at(top.x);
    // The lowest modes: the skew is not always the lowest (a nearly free orientation mode of
    // the fold pattern can lie below it), so every negative mode among the lowest three, or
    // the lowest if none is negative, is tried in both directions.
    const Eigenpairs lowest = modes_at(model, proxy, top.x, top.parameter, pins, o, false, 3);
    {
      PenalizedShell near(model, proxy, near_penalty_pairs(proxy, top.x, o), o);
      out.symmetric_top_energy = near.energy.evaluate(top.x, top.parameter, nullptr, nullptr);
    }
    LowestSkewedState choice(out.symmetric_top_energy, options.energy_margin);
    std::ostringstream m;
    m << "lowest eigenvalues at phi_e = " << top.parameter << ":";
    for (Eigen::Index k = 0; k < lowest.values.size(); ++k) m << ' ' << lowest.values[k];
    m << ";";
    // Where the start has the mirrors the symmetric branch was traced with (up to the rigid
    // motion between the subspace's frame and the caller's), each mode's class is noted; a mode
    // that lies in a class odd under a mirror s (T_s v = -v in that frame) makes the two pushes
    // images of each other under s, and with one_push_per_mirror_pair only the first is
    // relaxed. The modes of the pinned Hessian lie in a class only up to the pins, so the
    // second push starts next to the first's image, not on it.
    const SymmetricSubspace* mirrors = o.symmetric_subspace.get();
    std::optional<RigidMotion> to_mirror_frame;
    if (mirrors != nullptr && mirrors->full_dimension() == top.x.size() &&
        mirrors->group().classes_split_space()) {
      const RigidMotion motion = mirrors->aligning_motion(top.x);
      const double asymmetry = mirrors->asymmetry(motion.apply(top.x));
      if (asymmetry <= kMirrorImageAsymmetry * top.x.cwiseAbs().maxCoeff())
        to_mirror_frame = motion;
      else
        m << " the start is off its mirrors by " << asymmetry << " m: both pushes relaxed;";
    }
    for (Eigen::Index k = 0; k < lowest.values.size(); ++k) {
      if (k > 0 && !(lowest.values[k] < 0.0)) break;
      const Eigen::VectorXd mode = lowest.vectors.col(k);
      std::optional<ModeSymmetryClass> mode_class;
      if (to_mirror_frame) {
        mode_class = mode_symmetry_class(
            mirrors->group(),
            without_rigid_velocity(to_mirror_frame->apply(top.x), to_mirror_frame->rotate(mode)));
        m << " mode " << k << " without its rigid motion in the mirrors' class (";
        for (std::size_t g = 0; g < mode_class->generator_signs.size(); ++g)
          m << (g > 0 ? " " : "") << (mode_class->generator_signs[g] > 0 ? "+1" : "-1");
        m << "), part " << mode_class->weight << ";";
      }
      for (const int sign : {1, -1}) {
        if (sign < 0 && options.one_push_per_mirror_pair && mode_class && !mode_class->trivial() &&
            mode_class->weight >= kMirrorClassModeWeight) {
          m << " mode " << k << " push -1: not relaxed, next to the image of push 1 under "
            << "generator " << mode_class->odd_generator() << " of the mirrors;";
          ++out.skewed_pushes_skipped_as_images;
          continue;
        }
        Eigen::VectorXd y = top.x + sign * (options.push * h_c / mode.cwiseAbs().maxCoeff()) * mode;
        const ContactRelaxation relaxed =
            relax_with_contact(model, top.parameter, proxy, y, pins, o, options.relaxation);
        ++out.skewed_pushes_relaxed;
        // Iterations, not seconds: the note goes into results.json, which a rerun reproduces.
        const std::string cost =
            " (" + std::to_string(relaxed.newton_iterations) + " Newton iterations)";
        if (!relaxed.relaxed) {
          m << " mode " << k << " push " << sign << ": " << relaxed.message << cost << ";";
          continue;
        }
        const double energy = relaxed.energy;
        SelfIntersectionOptions si;
        si.exclusion_radius = o.exclusion_radius;
        const bool crossed = find_self_intersection(model, y, si).intersects;
        std::string why_not;
        const bool accepted = !options.accept_skewed || options.accept_skewed(y, why_not);
        m << " mode " << k << " push " << sign << ": energy " << energy << " (symmetric "
          << out.symmetric_top_energy << ")" << (crossed ? ", passes through itself" : "")
          << (accepted ? "" : ", not skewed: " + why_not) << cost << ";";
        if (!crossed && accepted) choice.offer(energy, y);
      }
    }
    out.skewed_search_seconds = std::chrono::duration<double>(Clock::now() - t_search).count();
    out.skewed_message = m.str();
    note(out.skewed_message);
    const Eigen::VectorXd& best = choice.state();
    if (choice.found() && options.verify_with_ipopt) {
      const auto t_ipopt = Clock::now();
      // Seeded with the penalty's own pair forces (penalty_warm_start.hpp).
      const ContactSolveResult seed = penalty_warm_start(
          proxy, near_penalty_pairs(proxy, best, o), best, o.contact_distance, o.stiffness);
      const ContactSolveResult check = solve_contact_equilibrium(
          model, top.parameter, proxy, best, pins, *options.verify_with_ipopt, &seed);
      out.ipopt_checked = true;
      out.ipopt_converged = check.converged;
      out.ipopt_message = check.message;
      const ShellEnergyBreakdown at_ipopt = model.energy_breakdown(check.x, top.parameter);
      const ShellEnergyBreakdown at_penalty = model.energy_breakdown(best, top.parameter);
      out.ipopt_energy = at_ipopt.stretching + at_ipopt.bending;
      out.penalty_elastic_energy = at_penalty.stretching + at_penalty.bending;
      out.ipopt_state_difference = (check.x - best).cwiseAbs().maxCoeff();
      out.ipopt_min_distance = check.min_distance;
      out.ipopt_seconds = std::chrono::duration<double>(Clock::now() - t_ipopt).count();
      std::ostringstream c;
      c << "Ipopt check of the skewed state: " << (check.converged ? "converged" : "failed") << " ("
        << check.message << "), elastic energy " << out.ipopt_energy << " (penalty "
        << out.penalty_elastic_energy << "), max state difference " << out.ipopt_state_difference
        << " m, smallest distance " << check.min_distance;
      note(c.str());
    }
    if (choice.found()) {
      out.skewed_found = true;
      out.skewed_relaxed_energy = choice.energy();
      if (options.skewed_subspace) {
        const std::string mismatch = subspace_start_mismatch(*options.skewed_subspace, best,
                                                             0.1 * h_c, "the skewed branch");
        if (mismatch.empty())
          skewed_options.symmetric_subspace = options.skewed_subspace;
        else
          note(mismatch);
      }
      if (options.skewed_phase_functional && !skewed_options.symmetric_subspace)
        skewed_options.phase_functional = options.skewed_phase_functional(best);
      // Downwards until the branch ends at a fold; the part beyond it comes back up, and the
      // trace stops when that part reaches the relaxed state's phi_e again (or, with
      // skewed_down_ends_at_fold, at the fold).
      ContactBranchOptions down_options = skewed_options;
      down_options.arclength.parameter_max = top.parameter;
      std::vector<BranchEvent> down_events;
      if (options.skewed_down_ends_at_fold) {
        down_events.push_back(turning_back_event(-1));
        down_options.arclength.fold_approach_tolerance = options.skewed_fold_approach_tolerance;
      }
      out.skewed_down = trace_contact_branch(
          model, proxy, best, top.parameter, Eigen::VectorXd::Zero(model.dimension()), -1.0, pins,
          down_options, on_skewed_sample(down_energy, down_negative), on_skewed_special,
          down_events);
      note("skewed branch, downwards: " + out.skewed_down.message);
      if (options.skewed_end > top.parameter) {
        out.skewed_up = trace_contact_branch(
            model, proxy, best, top.parameter, Eigen::VectorXd::Zero(model.dimension()), 1.0, pins,
            skewed_options, on_skewed_sample(up_energy, up_negative), on_skewed_special);
        note("skewed branch, upwards: " + out.skewed_up.message);
      }
    }
  }

  // phi_e^crit by energy. A skewed branch born at a branch point touches the symmetric one
  // there (energy difference ~ (phi - phi_b)^2): that tangency is not a crossing.
  const std::vector<BranchEnergySample> symmetric_joined =
      join_branch_samples(options.symmetric_before, symmetric_energy);
  if (symmetric_joined.size() >= 2) {
    struct Found {
      EnergyCrossing crossing;
      bool skewed_stable;  // both skewed samples around it are stable
    };
    std::vector<Found> found;
    const std::pair<const std::vector<BranchEnergySample>*, const std::vector<int>*> parts[] = {
        {&down_energy, &down_negative}, {&up_energy, &up_negative}};
    for (const auto& [part, negative] : parts) {
      if (part->size() < 2) continue;
      for (const EnergyCrossing& c : energy_crossings(symmetric_joined, *part)) {
        if (entered_at && std::abs(c.parameter - *entered_at) < options.tangency_exclusion)
          continue;
        // A skewed trace that ran through the subcritical branch point back onto the symmetric
        // branch interpolates the same energies as the symmetric samples: their "crossings"
        // (every interval, slope differences ~1e-7 of the slopes) are not crossings.
        const double slope_scale = std::max(std::abs(symmetric_joined[c.segment_a].energy_slope),
                                            std::abs((*part)[c.segment_b].energy_slope));
        if (std::abs(c.slope_difference) < options.coincidence_slope_ratio * slope_scale) continue;
        found.push_back({c, (*negative)[c.segment_b] == 0 && (*negative)[c.segment_b + 1] == 0});
      }
    }
    std::sort(found.begin(), found.end(), [](const Found& a, const Found& b) {
      return a.crossing.parameter < b.crossing.parameter;
    });
    // Both skewed traces can run over the same stretch of the branch (the downward one back up
    // past its fold, the upward one back down past its upper fold): one crossing each time.
    std::vector<Found> distinct;
    for (const Found& f : found) {
      if (!distinct.empty() &&
          std::abs(f.crossing.parameter - distinct.back().crossing.parameter) < 1e-5) {
        if (f.crossing.error_estimate < distinct.back().crossing.error_estimate)
          distinct.back().crossing = f.crossing;
        distinct.back().skewed_stable = distinct.back().skewed_stable || f.skewed_stable;
        continue;
      }
      distinct.push_back(f);
    }
    for (const Found& f : distinct) {
      out.crossings.push_back(f.crossing);
      out.crossing_skewed_stable.push_back(f.skewed_stable);
    }
  }
  return out;
}

}  // namespace growshell
