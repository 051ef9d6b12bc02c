#include "solvers/contact/contact_equilibrium.hpp"

#include "libshell/contact/edge_edge_distance.hpp"
#include "libshell/contact/point_triangle_distance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

namespace growshell {
namespace {

/// Exact (unmollified) distances of the pairs at proxy positions y, vertex-triangle pairs first.
/// Computed from the distance primitives directly: building ContactGapConstraints for them
/// (stencils and derivative patterns of every pair) cost 30 s for the 2.1 million candidates
/// of a three-segment proxy within 2 h, where the distances alone take a fraction of that.
Eigen::VectorXd pair_distances(const ContactProxy& proxy, const ContactCandidates& pairs,
                               const Eigen::MatrixX3d& y) {
  const Eigen::Index nvt = pairs.vertex_triangle.rows();
  Eigen::VectorXd d(nvt + pairs.edge_edge.rows());
  for (Eigen::Index k = 0; k < nvt; ++k) {
    const Eigen::Vector3i t = proxy.triangles.row(pairs.vertex_triangle(k, 1)).transpose();
    d(k) = std::sqrt(point_triangle_distance_squared(
        y.row(pairs.vertex_triangle(k, 0)).transpose(), y.row(t(0)).transpose(),
        y.row(t(1)).transpose(), y.row(t(2)).transpose()));
  }
  for (Eigen::Index k = 0; k < pairs.edge_edge.rows(); ++k) {
    const int a = pairs.edge_edge(k, 0), b = pairs.edge_edge(k, 1);
    d(nvt + k) = std::sqrt(edge_edge_distance_squared(
        y.row(proxy.edges(a, 0)).transpose(), y.row(proxy.edges(a, 1)).transpose(),
        y.row(proxy.edges(b, 0)).transpose(), y.row(proxy.edges(b, 1)).transpose()));
  }
  return d;
}

/// Sorted union of two sorted, duplicate-free pair lists.
Eigen::MatrixX2i merge_pairs(const Eigen::MatrixX2i& a, const Eigen::MatrixX2i& b) {
  std::vector<std::pair<int, int>> all;
  for (Eigen::Index i = 0; i < a.rows(); ++i) all.emplace_back(a(i, 0), a(i, 1));
  for (Eigen::Index i = 0; i < b.rows(); ++i) all.emplace_back(b(i, 0), b(i, 1));
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  Eigen::MatrixX2i out(static_cast<Eigen::Index>(all.size()), 2);
  for (std::size_t i = 0; i < all.size(); ++i) out.row(static_cast<Eigen::Index>(i)) << all[i].first, all[i].second;
  return out;
}

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

ContactCandidates merge_contact_pairs(const ContactCandidates& a, const ContactCandidates& b) {
  ContactCandidates out;
  out.vertex_triangle = merge_pairs(a.vertex_triangle, b.vertex_triangle);
  out.edge_edge = merge_pairs(a.edge_edge, b.edge_edge);
  return out;
}

double smallest_pair_distance(const ContactProxy& proxy, const ContactCandidates& pairs,
                              const Eigen::Ref<const Eigen::VectorXd>& x) {
  if (pairs.empty()) return std::numeric_limits<double>::infinity();
  return pair_distances(proxy, pairs, proxy_positions(proxy, x)).minCoeff();
}

ContactCandidates near_contact_pairs(const ContactProxy& proxy, const Eigen::Ref<const Eigen::VectorXd>& x,
                                     double distance, double exclusion_radius,
                                     const NearPairSelection& selection) {
  ContactCandidateOptions o;
  o.query_distance = distance;
  o.exclusion_radius = exclusion_radius;
  const Eigen::MatrixX3d y = proxy_positions(proxy, x);
  const ContactCandidates boxes = find_contact_candidates(proxy, y, o);
  if (boxes.empty()) return boxes;
  const Eigen::VectorXd d = pair_distances(proxy, boxes, y);
  std::vector<Eigen::Index> vt, ee;
  const Eigen::Index nvt = boxes.vertex_triangle.rows();
  for (Eigen::Index k = 0; k < d.size(); ++k) {
    if (!(d(k) < distance)) continue;
    if (k < nvt) {
      // Rows are sorted by vertex: a vertex's candidates are consecutive.
      if (selection.nearest_triangle_only && !vt.empty() &&
          boxes.vertex_triangle(vt.back(), 0) == boxes.vertex_triangle(k, 0)) {
        if (d(k) < d(vt.back())) vt.back() = k;
        continue;
      }
      vt.push_back(k);
    } else if (selection.edge_edge_pairs) {
      ee.push_back(k - nvt);
    }
  }
  ContactCandidates out;
  out.pairs_examined = boxes.pairs_examined;
  out.vertex_triangle.resize(static_cast<Eigen::Index>(vt.size()), 2);
  out.edge_edge.resize(static_cast<Eigen::Index>(ee.size()), 2);
  for (std::size_t i = 0; i < vt.size(); ++i)
    out.vertex_triangle.row(static_cast<Eigen::Index>(i)) = boxes.vertex_triangle.row(vt[i]);
  for (std::size_t i = 0; i < ee.size(); ++i)
    out.edge_edge.row(static_cast<Eigen::Index>(i)) = boxes.edge_edge.row(ee[i]);
  return out;
}

ContactSolveResult solve_contact_equilibrium(ShellModel& model, const ContactProxy& proxy,
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
      const NewtonResult r = NewtonSolver(options.newton).minimize(model, start, fixed_dofs);
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
      const ConstrainedResult r = minimize_with_constraints(model, constraints, start, fixed_dofs,
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
