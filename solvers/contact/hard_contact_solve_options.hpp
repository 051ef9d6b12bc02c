#pragma once
/// \file
/// Ipopt settings for re-solving a penalty-traced state under the hard constraints
/// gap >= contact distance: the econe_contact study's check of the skewed state and its
/// stage 7 (studies/hard_contact_check), and hard_contact_energy_crossing.

#include "libshell/assembly/shell_model.hpp"
#include "solvers/contact/contact_equilibrium.hpp"
#include "solvers/newton/newton_solver.hpp"

namespace growshell {

/// Vertex-triangle and edge-edge pairs (the penalty sees vertex-triangle pairs only, so a
/// re-solve also measures what edges crossing between proxy vertices change); tolerances
/// relative to the thickness h and the model's natural force scale, so that the multipliers are
/// contact forces resolved far below the forces of the shell; final gaps checked to 1e-2 h.
inline ContactSolveOptions hard_contact_solve_options(const ShellModel& model, double h,
                                                      double contact_distance,
                                                      double exclusion_radius,
                                                      double candidate_margin,
                                                      const NewtonOptions& newton) {
  ContactSolveOptions o;
  o.edge_edge_pairs = true;
  o.contact_distance = contact_distance;
  o.exclusion_radius = exclusion_radius;
  o.candidate_margin = candidate_margin;
  o.violation_tolerance = 1e-2 * h;
  o.minimizer.length_scale = h;
  o.minimizer.force_scale = model.natural_force_scale();
  o.minimizer.tolerance = 1e-8;
  o.minimizer.constraint_violation_tolerance = 1e-6 * h;
  o.minimizer.complementarity_tolerance = 1e-8 * model.natural_force_scale() * h;
  o.newton = newton;
  return o;
}

}  // namespace growshell
