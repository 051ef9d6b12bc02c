#pragma once
/// \file
/// The contact penalty a scene asks for, as every study sets it: one place for the contact
/// distance, the apex model's exclusion radius, the pair margin, the stiffness and the re-pinning
/// threshold, so that the econe_contact study's branches and the orientation check relax the
/// same energy, and the Newton settings of their relaxations of it.

#include "libshell/contact/contact_proxy.hpp"
#include "libshell/io/scene.hpp"
#include "libshell/assembly/shell_model.hpp"
#include "solvers/contact/contact_branch.hpp"
#include "solvers/newton/newton_solver.hpp"

namespace growshell {

/// The contact proxy a scene asks for: the limit surface of `model` sampled with
/// study.contact_proxy_segments segments per element edge (make_contact_proxy).
ContactProxy scene_contact_proxy(const Scene& scene, const ShellModel& model);

/// ContactBranchOptions with its penalty fields set from `scene` (h its thickness at the
/// centre): contact_distance physics.contact_distance (auto: h), exclusion_radius
/// resolved_exclusion_radius, candidate_margin h, stiffness study.penalty_stiffness_factor
/// Y l^2 / h with l the spacing of `proxy` (contact_stiffness_scale), violation_tolerance h / 4,
/// and repin_above_condition 20 (rim vertices pinned on the reference come round next to the
/// pinning axis as the cone grows), and the pairs' surface study.contact_surface (the limit
/// surface of `model` with that exclusion radius, or the proxy's triangles). The step control
/// and the stability index are left at their defaults for the caller. `proxy` must be
/// `model`'s.
ContactBranchOptions scene_contact_penalty(const Scene& scene, const ShellModel& model,
                                           const ContactProxy& proxy);

/// Newton settings of a relaxation of shell + the scene's penalty (the econe_contact study's
/// skewed search, its winding and the orientation check, before their own bounds): the force
/// tolerance study.tolerance of the model's natural force scale, the decrement test at
/// 1e-6 Y h^3 (it stops Newton's crawl along the nearly free turn of the fold pattern), 400
/// steps.
NewtonOptions scene_penalty_relaxation(const Scene& scene, const ShellModel& model);

}  // namespace growshell
