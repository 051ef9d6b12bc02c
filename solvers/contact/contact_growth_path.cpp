#include "solvers/contact/contact_growth_path.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "libshell/contact/contact_penalty.hpp"
#include "solvers/contact/contact_equilibrium.hpp"
#include "solvers/stability/lowest_eigenpairs.hpp"

namespace growshell {

namespace {

bool same_rows(const Eigen::MatrixX2i& a, const Eigen::MatrixX2i& b) {
  return a.rows() == b.rows() && a == b;
}

ContactCandidates near_pairs(const ContactProxy& proxy, const Eigen::VectorXd& y,
                             const ContactBranchOptions& o) {
  return near_contact_pairs(proxy, y, o.contact_distance + o.candidate_margin, o.exclusion_radius,
                            o.selection);
}

}  // namespace

bool relax_with_contact(ShellModel& model, const ContactProxy& proxy, Eigen::VectorXd& y,
                        const std::vector<Eigen::Index>& fixed_dofs,
                        const ContactBranchOptions& options, const NewtonOptions& newton,
                        double* energy, std::string* message, int max_rounds) {
  for (int round = 0; round < max_rounds; ++round) {
    const ContactCandidates pairs = near_pairs(proxy, y, options);
    ContactPenalty penalty(proxy, pairs, options.contact_distance, options.stiffness,
                           model.dimension(), options.gap);
    PenalizedEnergy total(model, penalty);
    const NewtonResult r = NewtonSolver(newton).minimize(total, y, fixed_dofs);
    y = r.x;
    if (!r.converged()) {
      *message = "relaxation failed: " + r.message;
      return false;
    }
    const ContactCandidates rebuilt = near_pairs(proxy, y, options);
    if (same_rows(rebuilt.vertex_triangle, pairs.vertex_triangle) &&
        same_rows(rebuilt.edge_edge, pairs.edge_edge)) {
      *energy = r.energy;
      return true;
    }
  }
  *message = "the pair set did not settle in " + std::to_string(max_rounds) + " relaxation rounds";
  return false;
}

ContactGrowthResult grow_with_contact(
    ShellModel& model, const ContactProxy& proxy, const Eigen::Ref<const Eigen::VectorXd>& x0,
    double phi0, double phi_target, const std::vector<Eigen::Index>& fixed_dofs,
    const ContactGrowthOptions& options,
    const std::function<void(const ContactGrowthPoint&)>& on_point) {
  if (!(options.max_step > 0.0 && options.min_step > 0.0 && options.min_step <= options.max_step))
    throw std::invalid_argument("ContactGrowthOptions: need 0 < min_step <= max_step");
  if (options.max_saddle_escapes < 0)
    throw std::invalid_argument("ContactGrowthOptions::max_saddle_escapes must be >= 0");
  const ContactBranchOptions& o = options.contact;
  const double direction = phi_target >= phi0 ? 1.0 : -1.0;
  ContactGrowthResult out;
  Eigen::VectorXd x = x0;
  double phi = phi0;
  double step = options.max_step;
  out.last.sample.sample.x = x0;
  out.last.sample.sample.parameter = phi0;
  while (direction * (phi_target - phi) > 1e-12) {
    const double next =
        direction > 0 ? std::min(phi + step, phi_target) : std::max(phi - step, phi_target);
    model.set_excess_angle(next);
    Eigen::VectorXd y = x;
    double energy = 0.0;
    std::string why;
    bool accepted = false;
    int escapes = 0;
    for (; escapes <= options.max_saddle_escapes; ++escapes) {
      if (!relax_with_contact(model, proxy, y, fixed_dofs, o, options.newton, &energy, &why)) break;
      // A strict minimum? The lowest eigenvalue of the penalised Hessian at the result.
      const ContactCandidates pairs = near_pairs(proxy, y, o);
      ContactPenalty penalty(proxy, pairs, o.contact_distance, o.stiffness, model.dimension(),
                             o.gap);
      PenalizedEnergy total(model, penalty);
      EigenpairOptions eig;
      eig.count = 1;
      const Eigenpairs lowest = lowest_eigenpairs(total, y, fixed_dofs, eig);
      if (lowest.values[0] > 0.0) {
        accepted = true;
        break;
      }
      // A saddle: push along the negative mode and minimise again.
      const Eigen::VectorXd mode = lowest.vectors.col(0);
      const double sign = escapes % 2 == 0 ? 1.0 : -1.0;
      y += sign * (0.5 * o.contact_distance / mode.cwiseAbs().maxCoeff()) * mode;
      why = "a saddle after " + std::to_string(escapes + 1) + " pushes";
    }
    if (!accepted) {
      ++out.failed_steps;
      step /= 2;
      if (step < options.min_step) {
        out.message = "step below min_step at phi_e = " + std::to_string(phi) + ": " + why;
        model.set_excess_angle(phi);
        return out;
      }
      continue;
    }
    ++out.steps;
    phi = next;
    x = y;
    BranchSample s;
    s.parameter = phi;
    s.x = x;
    s.tangent_state = Eigen::VectorXd::Zero(x.size());
    s.tangent_parameter = direction;
    ContactGrowthPoint point;
    point.sample = describe_contact_sample(model, proxy, s, near_pairs(proxy, x, o), o);
    point.saddle_escapes = escapes;
    point.jumped = escapes > 0;
    out.last = point;
    if (on_point) on_point(point);
    step = std::min(options.max_step, 1.5 * step);
  }
  out.reached_target = true;
  model.set_excess_angle(phi);
  return out;
}

}  // namespace growshell
