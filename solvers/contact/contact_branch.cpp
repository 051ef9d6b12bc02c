#include "solvers/contact/contact_branch.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <set>
#include <stdexcept>
#include <utility>

#include "core/objective_at_parameter.hpp"
#include "libshell/contact/contact_penalty.hpp"
#include "libshell/contact/equivariant_pairs.hpp"
#include "solvers/continuation/elastic_energy_slope.hpp"
#include "solvers/continuation/phase_condition_trace.hpp"
#include "solvers/continuation/phase_conditioned_family.hpp"
#include "solvers/continuation/subspace_branch_trace.hpp"
#include "solvers/newton/rigid_motion_pinning.hpp"

namespace growshell {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// Thrown from the segment's sample callback when a pair outside the segment's set came too
/// close: the segment ends there and is retried from the last accepted sample.
struct PairSetViolation {};

/// Thrown from the segment's sample callback when a special point at the segment boundary
/// makes ArclengthOptions::max_special_points of the whole trace: the trace ends there.
struct SpecialPointLimit {};

void validate(const ContactBranchOptions& o) {
  const auto positive = [](double v, const char* name) {
    if (!(std::isfinite(v) && v > 0.0))
      throw std::invalid_argument(std::string("ContactBranchOptions::") + name +
                                  " must be finite and > 0");
  };
  positive(o.contact_distance, "contact_distance");
  positive(o.exclusion_radius, "exclusion_radius");
  positive(o.candidate_margin, "candidate_margin");
  positive(o.stiffness, "stiffness");
  if (!(std::isfinite(o.violation_tolerance) && o.violation_tolerance >= 0.0 &&
        o.violation_tolerance < o.contact_distance))
    throw std::invalid_argument(
        "ContactBranchOptions::violation_tolerance must be in [0, contact_distance)");
  if (!(o.repin_above_condition >= 0.0))
    throw std::invalid_argument("ContactBranchOptions::repin_above_condition must be >= 0");
  if (o.start_residual_backtracks < 0)
    throw std::invalid_argument("ContactBranchOptions::start_residual_backtracks must be >= 0");
  if (o.steps_per_segment < 1)
    throw std::invalid_argument("ContactBranchOptions::steps_per_segment must be >= 1");
}

/// The sample's description with the penalty of its segment.
ContactBranchSample describe(const ShellModel& model, ContactPenalty* penalty,
                             const BranchSample& sample, const ContactCandidates& pairs,
                             const ContactProxy& proxy, const ContactBranchOptions& options) {
  ContactBranchSample out;
  out.sample = sample;
  out.pairs = pairs;
  const ShellEnergyBreakdown e = model.energy_breakdown(sample.x, sample.parameter);
  out.stretching_energy = e.stretching;
  out.bending_energy = e.bending;
  out.current_area = e.current_area;
  out.normalized_bending = e.normalized_bending();
  // dE/dphi at fixed state (P does not depend on phi_e).
  out.energy_slope = elastic_energy_slope(model, sample.x, sample.parameter);
  out.min_distance = std::numeric_limits<double>::infinity();
  out.forces = Eigen::VectorXd::Zero(0);
  if (!pairs.empty()) {
    std::optional<ContactPenalty> own;
    if (penalty == nullptr)
      penalty = &own.emplace(proxy, pairs, options.contact_distance, options.stiffness,
                             model.dimension(), options.gap);
    out.penalty_energy = penalty->evaluate(sample.x, nullptr, nullptr);
    const ContactGapConstraints& gaps = penalty->constraints();
    out.forces.resize(gaps.count());
    for (Eigen::Index k = 0; k < gaps.count(); ++k) {
      const ContactPairGeometry g = gaps.pair_geometry(sample.x, k);
      out.min_distance = std::min(out.min_distance, g.distance);
      // The penalty's force on the pair: k m (h - d)_+ (m: the edge-edge mollifier, else 1).
      out.forces[k] = options.stiffness * g.mollifier * std::max(0.0, -g.gap);
      if (out.forces[k] > 0.0) ++out.active_pairs;
    }
  }
  return out;
}

/// True if every pair of `close` is covered by `pairs`: a vertex-triangle pair by itself if
/// `same_triangle` (sets of every near triangle), else by any pair of the same proxy vertex
/// (sets of the nearest triangle, which is re-chosen at every rebuild); an edge-edge pair by
/// itself.
bool covered(const ContactCandidates& close, const ContactCandidates& pairs, bool same_triangle) {
  // Each vertex-triangle pair as (vertex, triangle), or (vertex, -1) where any triangle covers.
  const auto key = [same_triangle](const Eigen::MatrixX2i& m, Eigen::Index i) {
    return std::pair<int, int>{m(i, 0), same_triangle ? m(i, 1) : -1};
  };
  std::set<std::pair<int, int>> held;
  for (Eigen::Index i = 0; i < pairs.vertex_triangle.rows(); ++i)
    held.insert(key(pairs.vertex_triangle, i));
  for (Eigen::Index i = 0; i < close.vertex_triangle.rows(); ++i)
    if (!held.count(key(close.vertex_triangle, i))) return false;
  std::set<std::pair<int, int>> edges;
  for (Eigen::Index i = 0; i < pairs.edge_edge.rows(); ++i)
    edges.insert({pairs.edge_edge(i, 0), pairs.edge_edge(i, 1)});
  for (Eigen::Index i = 0; i < close.edge_edge.rows(); ++i)
    if (!edges.count({close.edge_edge(i, 0), close.edge_edge(i, 1)})) return false;
  return true;
}

}  // namespace

std::vector<Eigen::Index> rigid_pins_for_state(const ShellModel& model,
                                               const Eigen::Ref<const Eigen::VectorXd>& x,
                                               const std::vector<Eigen::Index>& pins,
                                               const ContactBranchOptions& options) {
  if (!(options.repin_above_condition > 0.0)) return pins;
  if (pins.size() != 6)
    throw std::invalid_argument(
        "repin_above_condition needs the six rigid-motion pins as fixed_dofs, got " +
        std::to_string(pins.size()) + " dofs");
  return well_conditioned_pins(
      Eigen::Map<const Eigen::Matrix<double, -1, 3, Eigen::RowMajor>>(x.data(), x.size() / 3, 3),
      pins, model.sheet_vertices(), options.repin_above_condition);
}

ContactBranchSample describe_contact_sample(const ShellModel& model, const ContactProxy& proxy,
                                            const BranchSample& sample,
                                            const ContactCandidates& pairs,
                                            const ContactBranchOptions& options) {
  validate(options);
  return describe(model, nullptr, sample, pairs, proxy, options);
}

namespace {

/// A segment start relaxed by minimisation on the pair set rebuilt there, and again at each
/// result until it is an equilibrium of the set built there, or of a set that holds it.
struct StartRelaxation {
  bool settled = false;
  Eigen::VectorXd x;
  /// The set x is an equilibrium of, where it is not the one built at x: the union of the
  /// sets built at the results (a vertex in a valley of the other layer, whose nearest
  /// triangle flips between its two sides from one minimum to the next, keeps both).
  std::optional<ContactCandidates> pairs;
  std::string message;  ///< why not, if not settled
};

StartRelaxation relax_segment_start(const ShellModel& model, const ContactProxy& proxy,
                                    const Eigen::VectorXd& start, double phi,
                                    ContactCandidates pairs, const std::vector<Eigen::Index>& fixed,
                                    double margin, const NewtonOptions& relaxation,
                                    const ContactBranchOptions& options,
                                    const std::vector<ProxySymmetry>& proxy_group) {
  constexpr int kRounds = 6;
  StartRelaxation out;
  out.x = start;
  for (int round = 0; round < kRounds; ++round) {
    ContactPenalty penalty(proxy, pairs, options.contact_distance, options.stiffness,
                           model.dimension(), options.gap);
    PenalizedEnergy family(model, penalty);
    ObjectiveAtParameter at(family, phi);
    const NewtonResult r = NewtonSolver(relaxation).minimize(at, out.x, fixed);
    if (r.status != NewtonStatus::Converged) {
      out.message = "round " + std::to_string(round + 1) + ": " + r.message;
      return out;
    }
    out.x = r.x;
    ContactCandidates own_pairs =
        near_contact_pairs(proxy, out.x, options.contact_distance + margin,
                           options.exclusion_radius, options.selection);
    // In a subspace the sets are closed under its symmetries, and so is their union.
    if (!proxy_group.empty()) own_pairs = equivariant_nearest_pairs(own_pairs, proxy_group);
    ContactPenalty own(proxy, own_pairs, options.contact_distance, options.stiffness,
                       model.dimension(), options.gap);
    PenalizedEnergy own_family(model, own);
    Eigen::VectorXd g;
    own_family.evaluate(out.x, phi, &g, nullptr);
    for (const Eigen::Index i : fixed) g[i] = 0.0;  // reactions of the held dofs
    if (g.lpNorm<Eigen::Infinity>() <= relaxation.gradient_tolerance) {
      out.settled = true;
      return out;
    }
    // Otherwise minimise again with the union of the two sets, which only grows; once it
    // holds the set built at its own minimum, that minimum (converged on the force, the
    // caller's decrement test being off) misses no contact and the segment goes on with the
    // union.
    const ContactCandidates merged = merge_contact_pairs(pairs, own_pairs);
    if (merged.size() == pairs.size()) {
      out.settled = true;
      out.pairs = pairs;
      return out;
    }
    pairs = merged;
  }
  out.message =
      "not an equilibrium of the pair set built at its minimum, nor of a union of "
      "such sets, after " +
      std::to_string(kRounds) + " rounds";
  return out;
}

}  // namespace

ContactBranchTrace trace_contact_branch(
    const ShellModel& model, const ContactProxy& proxy, const Eigen::Ref<const Eigen::VectorXd>& x0,
    double phi0, const Eigen::Ref<const Eigen::VectorXd>& direction_state,
    double direction_parameter, const std::vector<Eigen::Index>& fixed_dofs,
    const ContactBranchOptions& options,
    const std::function<void(const ContactBranchSample&)>& on_sample,
    const std::function<void(const SpecialPoint&)>& on_special,
    const std::vector<BranchEvent>& events,
    const std::function<void(const LocatedEvent&)>& on_event) {
  validate(options);
  if (x0.size() != model.dimension() || direction_state.size() != model.dimension())
    throw std::invalid_argument("trace_contact_branch: x0 and direction_state need " +
                                std::to_string(model.dimension()) + " entries");
  if (options.symmetric_subspace &&
      options.symmetric_subspace->full_dimension() != model.dimension())
    throw std::invalid_argument("ContactBranchOptions::symmetric_subspace is for " +
                                std::to_string(options.symmetric_subspace->full_dimension()) +
                                " unknowns, the model has " + std::to_string(model.dimension()));
  if (options.phase_functional.size() > 0) {
    if (options.phase_functional.size() != model.dimension())
      throw std::invalid_argument("ContactBranchOptions::phase_functional needs " +
                                  std::to_string(model.dimension()) + " entries, it has " +
                                  std::to_string(options.phase_functional.size()));
    const double norm = options.phase_functional.norm();
    if (!(norm > 0.0) || !std::isfinite(norm))
      throw std::invalid_argument(
          "ContactBranchOptions::phase_functional must be finite and not vanish");
    if (options.symmetric_subspace)
      throw std::invalid_argument(
          "ContactBranchOptions: phase_functional and symmetric_subspace cannot both be set");
  }
  // The unit functional whose multiplier each sample reports as its phase force.
  const Eigen::VectorXd phase_unit = options.phase_functional.size() > 0
                                         ? Eigen::VectorXd(options.phase_functional.normalized())
                                         : Eigen::VectorXd();
  ContactBranchTrace out;
  std::vector<Eigen::Index> segment_fixed = fixed_dofs;
  const ArclengthOptions& arc = options.arclength;
  // In a symmetric subspace every segment is traced by trace_branch_in_subspace, which hands
  // back full states in this frame.
  const SymmetricSubspace* subspace = options.symmetric_subspace.get();
  Eigen::VectorXd start_x = x0, start_direction = direction_state;
  double start_phi = phi0, start_direction_parameter = direction_parameter;
  double step = arc.initial_step;
  double margin = options.candidate_margin;
  bool have_sample = false;  // out.last holds a converged sample
  int retries = 0;
  // The sample one step before the last segment's end: where a segment whose start does not
  // converge on its rebuilt pair set is retried from, with a shorter step and a wider margin.
  BranchSample fallback;
  bool have_fallback = false;
  // This segment's start failed before and is corrected with halved updates.
  bool safeguarded = false;
  // This segment's start failed that too and was relaxed by minimisation.
  bool relaxed = false;
  // The pair set of the next segment, where its relaxed start is an equilibrium of a union of
  // sets rather than of the set built at it (relax_segment_start).
  std::optional<ContactCandidates> relaxed_start_pairs;
  // The step control's growth pause after a failed step (ArclengthOptions::
  // growth_pause_after_failure), carried from segment to segment.
  int growth_pause = arc.initial_growth_pause;
  // A set of every near triangle must hold a sample's close pairs themselves, not just a pair
  // of the same vertex.
  const bool exact_cover = !options.selection.nearest_triangle_only;
  // The subspace's symmetries as maps of the proxy, for pair sets closed under them.
  std::vector<ProxySymmetry> proxy_group;
  if (subspace && options.symmetric_pair_sets && options.selection.nearest_triangle_only) {
    std::vector<Eigen::Vector3d> signs;
    for (const VertexSymmetry& g : subspace->group().generators()) signs.push_back(g.signs);
    proxy_group = proxy_symmetry_group(
        proxy, signs, 1e-9 * std::max(1.0, proxy.reference_positions.cwiseAbs().maxCoeff()));
  }
  while (out.steps < arc.max_steps) {
    // The pair set of this segment: pairs near its start.
    auto t0 = Clock::now();
    ContactCandidates pairs;
    if (relaxed_start_pairs) {
      // relax_segment_start's union, closed under the subspace's symmetries if there is one.
      pairs = *std::exchange(relaxed_start_pairs, std::nullopt);
    } else {
      pairs = near_contact_pairs(proxy, start_x, options.contact_distance + margin,
                                 options.exclusion_radius, options.selection);
      if (!proxy_group.empty()) pairs = equivariant_nearest_pairs(pairs, proxy_group);
    }
    out.cost.pair_search_seconds += seconds_since(t0);
    const std::vector<Eigen::Index> pins =
        rigid_pins_for_state(model, start_x, segment_fixed, options);
    if (pins != segment_fixed) {
      segment_fixed = pins;
      ++out.cost.repinnings;
      // The tangent carried over moves only free dofs of the new gauge.
      for (const Eigen::Index d : segment_fixed) start_direction(d) = 0.0;
    }
    ContactPenalty penalty(proxy, pairs, options.contact_distance, options.stiffness,
                           model.dimension(), options.gap);
    PenalizedEnergy family(model, penalty);
    ArclengthOptions segment_options = arc;
    if (options.stability_index_for_segment)
      segment_options.stability_index = options.stability_index_for_segment(family, subspace);
    if (safeguarded) {
      // Halved updates converge from there, but slowly while the iterates cross pieces of
      // the penalty's Hessian: twice the iterations.
      segment_options.max_residual_backtracks =
          std::max(arc.max_residual_backtracks, options.start_residual_backtracks);
      segment_options.max_corrector_iterations = 2 * arc.max_corrector_iterations;
      segment_options.start_corrector_iterations =
          2 * std::max(arc.start_corrector_iterations, arc.max_corrector_iterations);
    }
    segment_options.initial_step = std::clamp(step, arc.min_step, arc.max_step);
    segment_options.initial_growth_pause = growth_pause;
    segment_options.max_steps = std::min(options.steps_per_segment, arc.max_steps - out.steps);
    // The limit on special points holds for the whole trace, not each segment.
    if (arc.max_special_points > 0)
      segment_options.max_special_points =
          arc.max_special_points - static_cast<int>(out.special_points.size());
    const int segment = out.cost.segments++;

    const bool emit_start = !have_sample;
    int samples_in_segment = 0;
    BranchSample last_good, before_last_good;
    bool have_last_good = false, have_before_last_good = false;
    double previous_arclength = 0.0, last_step = step;
    const auto on_segment_sample = [&](const BranchSample& s) {
      auto tc = Clock::now();
      const ContactCandidates close =
          near_contact_pairs(proxy, s.x, options.contact_distance - options.violation_tolerance,
                             options.exclusion_radius, options.selection);
      out.cost.pair_search_seconds += seconds_since(tc);
      if (!covered(close, pairs, exact_cover)) throw PairSetViolation{};
      const bool is_start = samples_in_segment++ == 0;
      if (!is_start) {
        last_step = s.arclength - previous_arclength;
        ++out.steps;
      }
      previous_arclength = s.arclength;
      if (have_last_good) {
        before_last_good = last_good;
        have_before_last_good = true;
      }
      last_good = s;
      have_last_good = true;
      if (is_start && !emit_start) {
        // The previous segment's last sample, corrected on the rebuilt pair set: a change of
        // the negative count here is a special point at the segment boundary.
        if (s.negative_eigenvalues != out.last.sample.negative_eigenvalues) {
          SpecialPoint sp;
          sp.kind = (s.tangent_parameter > 0) == (out.last.sample.tangent_parameter > 0)
                        ? SpecialPoint::Kind::BranchPoint
                        : SpecialPoint::Kind::Fold;
          sp.parameter = s.parameter;
          sp.x = s.x;
          sp.negative_before = out.last.sample.negative_eigenvalues;
          sp.negative_after = s.negative_eigenvalues;
          sp.multiplicity = std::abs(sp.negative_after - sp.negative_before);
          sp.bracket_width = std::abs(s.parameter - out.last.sample.parameter);
          out.special_points.push_back(sp);
          if (on_special) on_special(sp);
        }
        out.last.sample = s;
        if (arc.max_special_points > 0 &&
            static_cast<int>(out.special_points.size()) >= arc.max_special_points)
          throw SpecialPointLimit{};
        return;
      }
      auto td = Clock::now();
      ContactBranchSample described = describe(model, &penalty, s, pairs, proxy, options);
      described.segment = segment;
      if (phase_unit.size() > 0) {
        Eigen::VectorXd g;
        family.evaluate(s.x, s.parameter, &g, nullptr);
        described.phase_force = std::abs(phase_multiplier(g, phase_unit, segment_fixed));
      }
      out.cost.sample_seconds += seconds_since(td);
      out.last = std::move(described);
      have_sample = true;
      if (on_sample) on_sample(out.last);
    };

    BranchTrace trace;
    bool violated = false, limit_reached = false;
    t0 = Clock::now();
    try {
      if (subspace) {
        trace = trace_branch_in_subspace(family, *subspace, start_x, start_phi, start_direction,
                                         start_direction_parameter, segment_fixed, segment_options,
                                         on_segment_sample, on_special, events, on_event);
      } else if (options.phase_functional.size() > 0) {
        trace = trace_branch_with_phase_condition(
            family, options.phase_functional, start_x, start_phi, start_direction,
            start_direction_parameter, segment_fixed, segment_options, on_segment_sample,
            on_special, events, on_event);
      } else {
        trace = trace_branch_along(family, start_x, start_phi, start_direction,
                                   start_direction_parameter, segment_fixed, segment_options,
                                   on_segment_sample, on_special, events, on_event);
      }
    } catch (const PairSetViolation&) {
      violated = true;
    } catch (const SpecialPointLimit&) {
      limit_reached = true;
    }
    if (limit_reached) {
      out.cost.continuation.total_seconds += seconds_since(t0);
      out.reached_bound = true;
      out.message = "found max_special_points special points";
      break;
    }
    if (violated) {
      // The cost of the abandoned segment is known only in wall time.
      out.cost.continuation.total_seconds += seconds_since(t0);
      ++out.cost.rebuilds_after_violation;
      if (++retries > 6)
        throw std::runtime_error(
            "trace_contact_branch: pairs keep coming closer than allowed "
            "after 6 rebuilds at phi_e = " +
            std::to_string(start_phi));
      if (have_last_good && samples_in_segment > 1) {
        // Restart from the last accepted sample with a set rebuilt there.
        start_x = last_good.x;
        start_phi = last_good.parameter;
        start_direction = last_good.tangent_state;
        start_direction_parameter = last_good.tangent_parameter;
        step = last_step;
      } else {
        // Even the first step moved a pair further than the margin: widen it, shorten steps.
        margin *= 2.0;
        step /= 2.0;
      }
      continue;
    }
    retries = 0;
    margin = options.candidate_margin;
    if (samples_in_segment > 0) safeguarded = relaxed = false;
    out.cost.continuation += trace.cost;
    for (const SpecialPoint& sp : trace.special_points) out.special_points.push_back(sp);
    for (const LocatedEvent& e : trace.events) out.events.push_back(e);
    out.failed_steps += trace.failed_steps;
    growth_pause = trace.growth_pause_left;
    if (samples_in_segment == 0) {
      // The start, an equilibrium on the previous pair set, did not converge on the rebuilt
      // one (pairs that enter between the two sets can change the forces abruptly). Step back
      // one sample and go on with a shorter step and a wider margin, so that those pairs enter
      // the set while they are still farther than the contact distance.
      if (have_fallback) {
        ++out.cost.rebuilds_after_violation;
        start_x = fallback.x;
        start_phi = fallback.parameter;
        start_direction = fallback.tangent_state;
        start_direction_parameter = fallback.tangent_parameter;
        step = std::max(0.5 * step, arc.min_step);
        margin *= 2.0;
        have_fallback = false;  // one step back only
        continue;
      }
      if (!safeguarded && options.start_residual_backtracks > arc.max_residual_backtracks) {
        // The same start once more, with Newton's updates halved where they raise the
        // residual; a second failure ends the trace.
        safeguarded = true;
        ++out.cost.safeguarded_starts;
        continue;
      }
      std::string relaxation_note;
      if (!relaxed && options.start_relaxation) {
        // The minimum of the rebuilt set's energy next to the start, found by a minimisation
        // whose line search keeps it from diverging. The next segment's set is built at that
        // minimum, where a vertex's nearest triangle can differ again: the minimisation is
        // repeated on the set built at its result until the result is an equilibrium of it.
        relaxed = true;
        ++out.cost.relaxed_starts;
        NewtonOptions relaxation = *options.start_relaxation;
        relaxation.max_travel = std::min(relaxation.max_travel, margin);
        // The corrector starts from the minimum only if its force is within the corrector's
        // tolerance; a minimisation stopped by its decrement can leave it 100 times above on
        // the penalty's stiff Hessian (measured: 1.5e-4 N against 1e-6 N).
        relaxation.gradient_tolerance =
            std::min(relaxation.gradient_tolerance, arc.gradient_tolerance);
        relaxation.decrement_tolerance = 0.0;
        // In a subspace the minimisation runs in the full space, from a symmetric start on a
        // symmetric energy (the sets closed under the subspace's symmetries), and the next
        // segment aligns and projects its result.
        const StartRelaxation r =
            relax_segment_start(model, proxy, start_x, start_phi, pairs, segment_fixed, margin,
                                relaxation, options, proxy_group);
        if (r.settled) {
          start_x = r.x;
          relaxed_start_pairs = r.pairs;
          continue;
        }
        relaxation_note = "; relaxed on the rebuilt pair set: " + r.message;
      }
      out.message = "segment start at phi_e = " + std::to_string(start_phi) +
                    " did not converge: " + trace.message + relaxation_note;
      break;
    }
    if (trace.reached_bound && trace.message != "reached max_steps") {
      out.reached_bound = true;
      out.message = trace.message;
      out.approached_fold = trace.approached_fold;
      out.fold_parameter = trace.fold_parameter;
      break;
    }
    if (trace.message != "reached max_steps") {
      out.message = trace.message;
      break;
    }
    if (have_before_last_good) {
      fallback = before_last_good;
      have_fallback = true;
    }
    start_x = trace.last.x;
    start_phi = trace.last.parameter;
    start_direction = trace.last.tangent_state;
    start_direction_parameter = trace.last.tangent_parameter;
    step = last_step;
  }
  if (out.message.empty()) {
    out.message = "reached max_steps";
    out.reached_bound = true;
  }
  return out;
}

}  // namespace growshell
