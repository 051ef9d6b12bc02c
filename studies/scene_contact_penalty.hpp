#pragma once
/// \file
/// The contact penalty a scene asks for, as every study sets it: one place for the contact
/// distance, the apex model's exclusion radius, the pair margin, the stiffness and the re-pinning
/// threshold, so that the econe_contact study's branches and the orientation check relax the
/// same energy.

#include "libshell/contact/contact_proxy.hpp"
#include "libshell/io/scene.hpp"
#include "solvers/contact/contact_branch.hpp"

namespace growshell {

/// ContactBranchOptions with its penalty fields set from `scene` (h its thickness at the
/// centre): contact_distance physics.contact_distance (auto: h), exclusion_radius
/// resolved_exclusion_radius, candidate_margin h, stiffness study.penalty_stiffness_factor
/// Y l^2 / h with l the spacing of `proxy` (contact_stiffness_scale), violation_tolerance h / 4,
/// and repin_above_condition 20 (rim vertices pinned on the reference come round next to the
/// pinning axis as the cone grows). The step control and the stability index are left at their
/// defaults for the caller.
ContactBranchOptions scene_contact_penalty(const Scene& scene, const ContactProxy& proxy);

}  // namespace growshell
