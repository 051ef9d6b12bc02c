#include "solvers/contact/contact_equilibrium.hpp"

#include "core/objective_at_parameter.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <tuple>

#include "libshell/contact/near_contact_pairs.hpp"

namespace growshell {
namespace {

/// Pair key: (type, first, second) with type 0 = vertex-triangle, 1 = edge-edge.
std::map<std::tuple<int, int, int>, double> force_by_pair(const ContactSolveResult& r) {
  std::map<std::tuple<int, int, int>, double> out;
  const Eigen::Index nvt = r.pairs.vertex_triangle.rows();
  for (Eigen::Index k = 0; k < r.forces.size(); ++k) {
    if (k < nvt)
      out[{0, r.pairs.vertex_triangle(k, 0), r.pairs.vertex_triangle(k, 1)}] = r.forces(k);
    else
      out[{1, r.pairs.edge_edge(k - nvt, 0), r.pairs.edge_edge(k - nvt, 1)}] = r.forces(k);
  }
  return out;
}

}  // namespace

ContactSolveResult solve_contact_equilibrium(const ShellModel& model, double excess_angle,
                                             const ContactProxy& proxy,
                                             const Eigen::Ref<const Eigen::VectorXd>& x0,
                                             const std::vector<Eigen::Index>& fixed_dofs,
                                             const ContactSolveOptions& options,
                                             const ContactSolveResult* warm) {
  // Finite too: an infinite distance would surface as an error about the broad phase's
  // query_distance, and an infinite violation_tolerance would silently accept any crossing.
  if (!(std::isfinite(options.contact_distance) && options.contact_distance > 0.0))
    throw std::invalid_argument("ContactSolveOptions: contact_distance must be finite and > 0");
  if (!(std::isfinite(options.exclusion_radius) && options.exclusion_radius > 0.0))
    throw std::invalid_argument("ContactSolveOptions: exclusion_radius must be finite and > 0");
  if (!(std::isfinite(options.candidate_margin) && options.candidate_margin > 0.0))
    throw std::invalid_argument("ContactSolveOptions: candidate_margin must be finite and > 0");
  if (options.max_rounds < 1) throw std::invalid_argument("ContactSolveOptions: max_rounds must be >= 1");
  if (!(std::isfinite(options.violation_tolerance) && options.violation_tolerance >= 0.0))
    throw std::invalid_argument("ContactSolveOptions: violation_tolerance must be finite and >= 0");
  // Its multipliers are matched to the candidate rows pair by pair, which the limit surface's
  // merged pairs do not keep.
  if (options.gap.limit_surface)
    throw std::invalid_argument(
        "ContactSolveOptions: gap.limit_surface is not supported by the hard-contact solve "
        "(its pairs are measured on the proxy's triangles)");
  ObjectiveAtParameter energy(model, excess_angle);
  if (x0.size() != model.dimension())
    throw std::invalid_argument("solve_contact_equilibrium: x0 has the wrong size");

  const double reach = options.contact_distance + options.candidate_margin;
  const double allowed = options.contact_distance - options.violation_tolerance;
  ContactSolveResult out;
  out.x = x0;
  const Eigen::VectorXd start = x0;
  NearPairSelection selection;
  selection.edge_edge_pairs = options.edge_edge_pairs;
  selection.nearest_triangle_only = options.nearest_triangle_only;
  ContactCandidates pairs = near_contact_pairs(proxy, start, reach, options.exclusion_radius, selection);
  if (warm) pairs = merge_contact_pairs(pairs, warm->pairs);  // keep the contacts of the previous point

  for (int round = 1; round <= options.max_rounds; ++round) {
    out.rounds = round;
    Eigen::VectorXd x;
    if (pairs.empty()) {
      // Nothing near: plain Newton, no contact cost beyond the broad phase.
      const NewtonResult r = NewtonSolver(options.newton).minimize(energy, start, fixed_dofs);
      out.iterations += r.iterations;
      out.used_contact = false;
      out.forces.resize(0);
      out.pairs = pairs;
      x = r.x;
      out.x = x;
      if (!r.converged()) {
        out.message = "Newton (no contact): " + r.message;
        return out;
      }
    } else {
      ContactGapConstraints constraints(proxy, pairs, options.contact_distance, model.dimension(),
                                        options.gap);
      Eigen::VectorXd seed;
      if (warm && warm->forces.size() > 0) {
        const auto previous = force_by_pair(*warm);
        seed = Eigen::VectorXd::Zero(constraints.count());
        const Eigen::Index nvt = pairs.vertex_triangle.rows();
        for (Eigen::Index k = 0; k < seed.size(); ++k) {
          const auto key = k < nvt ? std::make_tuple(0, pairs.vertex_triangle(k, 0), pairs.vertex_triangle(k, 1))
                                   : std::make_tuple(1, pairs.edge_edge(k - nvt, 0), pairs.edge_edge(k - nvt, 1));
          const auto it = previous.find(key);
          // Ipopt returns multipliers of inactive pairs as tiny numbers of either sign.
          if (it != previous.end()) seed(k) = std::max(0.0, it->second);
        }
      }
      const ConstrainedResult r = minimize_with_constraints(energy, constraints, start, fixed_dofs,
                                                            options.minimizer,
                                                            seed.size() ? &seed : nullptr);
      out.iterations += r.iterations;
      out.used_contact = true;
      out.pairs = pairs;
      out.forces = r.multipliers;
      x = r.x;
      out.x = x;
      if (!r.converged()) {
        out.message = r.message;
        return out;
      }
    }
    // Verify against every pair near the solution (edge-edge pairs and all triangles
    // included, whatever the selection of constrained pairs), not only the constrained ones.
    const ContactCandidates violators = near_contact_pairs(proxy, x, allowed, options.exclusion_radius);
    out.min_distance = std::min(smallest_pair_distance(proxy, pairs, x), smallest_pair_distance(proxy, violators, x));
    if (violators.empty() && out.min_distance >= allowed) {
      out.converged = true;
      out.message = out.used_contact ? "converged with contact" : "converged without contact";
      return out;
    }
    // Some pair came closer than allowed without being constrained: add the selected pairs
    // now within reach (cheap: nearest triangles) and, only if that adds nothing, the
    // violating pairs themselves; then solve again from the feasible start. If nothing new
    // can be added, another round would repeat the same solve. (A union contains `pairs`, so
    // it added nothing iff it has as many pairs.)
    ContactCandidates next =
        merge_contact_pairs(pairs, near_contact_pairs(proxy, x, reach, options.exclusion_radius, selection));
    if (next.size() == pairs.size()) next = merge_contact_pairs(next, violators);
    if (next.size() == pairs.size()) {
      out.message = "a constrained pair ends closer than allowed (min distance " +
                    std::to_string(out.min_distance) + " m); tighten the minimiser's tolerances";
      return out;
    }
    pairs = next;
  }
  out.message = "a pair is still closer than the contact distance after " +
                std::to_string(options.max_rounds) + " rounds (min distance " +
                std::to_string(out.min_distance) + " m)";
  return out;
}

}  // namespace growshell
