#include "studies/scene_contact_penalty.hpp"

#include "libshell/contact/contact_penalty.hpp"

namespace growshell {

ContactBranchOptions scene_contact_penalty(const Scene& scene, const ContactProxy& proxy) {
  const double h = thickness_at_radius(scene.thickness, 0.0, scene.geometry.radius);
  ContactBranchOptions c;
  c.contact_distance = scene.physics.contact_distance.value_or(h);
  c.exclusion_radius = resolved_exclusion_radius(scene);
  c.candidate_margin = h;
  c.stiffness =
      scene.study.penalty_stiffness_factor *
      contact_stiffness_scale(scene.material.youngs_modulus, h, proxy_mean_edge_length(proxy));
  c.violation_tolerance = 0.25 * h;
  c.repin_above_condition = 20.0;
  return c;
}

}  // namespace growshell
