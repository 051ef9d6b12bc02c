#pragma once
/// \file
/// A penalty-traced state solved again under Ipopt's hard contact constraints, and the two
/// compared: the contact solver of record at a reported point. The studies trace their
/// branches through contact with the penalty (h - d)_+^2, which lets pairs come a little closer
/// than the contact distance; here the state is solved again with gap >= contact distance on
/// vertex-triangle and edge-edge pairs (hard_contact_solve_options), starting from the
/// penalty's state with the penalty's pair forces as the multipliers (penalty_warm_start), and
/// the elastic energies, states, smallest pair distances, S4 defects and gamma of the two
/// solutions are set side by side. `hard_contact_at` (a program) and the econe_contact study's
/// `study.hard_contact_at` use it.

#include <Eigen/Core>
#include <string>

#include "libshell/assembly/shell_model.hpp"
#include "libshell/contact/contact_proxy.hpp"
#include "libshell/io/scene.hpp"
#include "solvers/continuation/pseudo_arclength.hpp"

namespace growshell {

/// The comparison. Energies in J, angles in radians; NaN where a measure is undefined (no
/// fold directions for S4, fewer than two contact zones for gamma; +infinity for a distance
/// with no pair within 2 contact distances).
struct HardContactCheck {
  double phi_e = 0.0;            ///< the state's excess angle
  Eigen::Index unknowns = 0;
  bool converged = false;        ///< Ipopt converged with every pair at >= h - 1e-2 h
  std::string message;           ///< solve_contact_equilibrium's
  double seconds = 0.0;          ///< wall time of the solve
  int rounds = 0;                ///< solves with an enlarged pair set
  int iterations = 0;            ///< Ipopt iterations over the rounds
  double penalty_elastic_energy = 0.0;  ///< E_s + E_b of the penalty's state
  double hard_elastic_energy = 0.0;     ///< E_s + E_b of the hard solution
  /// (penalty - hard) / hard.
  double relative_energy_difference = 0.0;
  double state_difference_over_h = 0.0;  ///< max |x_hard - x_penalty| / h
  /// Smallest distance over the pairs beyond the exclusion radius (edge-edge included), / h.
  double penalty_min_distance_over_h = 0.0;
  double hard_min_distance_over_h = 0.0;
  double penalty_s4_defect = 0.0;
  double hard_s4_defect = 0.0;
  /// gamma (cone_contact_plane_angle) from the penalty's pair forces k (h - d)_+ and from
  /// Ipopt's multipliers.
  double penalty_gamma = 0.0;
  double hard_gamma = 0.0;
  Eigen::VectorXd x;  ///< the hard solution (finite; the penalty's state if Ipopt failed at once)
};

/// Solves `state` (a sample of a branch traced with the penalty of `scene`, on `model` and
/// its contact `proxy`) again under the hard constraints and compares. The penalty and the
/// Newton settings are the studies' (scene_orientation_check_options); the rigid motions are
/// pinned as the stability analyses pin them. `ipopt_print_level` > 0 lets Ipopt print its
/// iteration log on stdout (a diagnostic for programs; 0, the default, prints nothing).
/// Throws std::invalid_argument if the state has the wrong size, and as the solver for bad
/// settings.
HardContactCheck check_hard_contact(const Scene& scene, const ShellModel& model,
                                    const ContactProxy& proxy, const BranchSample& state,
                                    int ipopt_print_level = 0);

/// The check as a JSON object (every field but x, in the order above; non-finite numbers as
/// null), ending with a newline.
std::string hard_contact_check_json(const HardContactCheck& check);

}  // namespace growshell
