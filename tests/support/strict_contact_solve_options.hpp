#pragma once
// Hard-contact settings for the contact solver's small test scenes: tolerances far below what
// the tests assert, so that what they measure is the scene, not the solver's stopping point.
// h is the contact distance (m) and `force` the scene's force scale (N).
#include "solvers/contact/contact_equilibrium.hpp"

namespace growshell::test_support {

constexpr double kStrictContactPi = 3.14159265358979323846;

/// Exclusion radius pi h / 2, candidate margin h / 4, final gaps to 1e-6 h; Ipopt to 1e-10
/// (acceptable 1e-8), constraint violation 1e-9 h, complementarity 1e-10 h force, dual
/// infeasibility and Newton's gradient 1e-10 force.
inline ContactSolveOptions strict_contact_solve_options(double h, double force) {
  ContactSolveOptions o;
  o.contact_distance = h;
  o.exclusion_radius = 0.5 * kStrictContactPi * h;
  o.candidate_margin = 0.25 * h;
  o.violation_tolerance = 1e-6 * h;
  o.minimizer.length_scale = h;
  o.minimizer.force_scale = force;
  o.minimizer.tolerance = 1e-10;
  o.minimizer.acceptable_tolerance = 1e-8;
  o.minimizer.constraint_violation_tolerance = 1e-9 * h;
  o.minimizer.complementarity_tolerance = 1e-10 * h * force;
  o.minimizer.dual_infeasibility_tolerance = 1e-10 * force;
  o.newton.gradient_tolerance = 1e-10 * force;
  return o;
}

}  // namespace growshell::test_support
