#include "studies/scene_contact_penalty.hpp"

#include "libshell/contact/contact_penalty.hpp"
#include "libshell/contact/limit_surface_contact.hpp"

namespace growshell {

ContactProxy scene_contact_proxy(const Scene& scene, const ShellModel& model) {
  return make_contact_proxy(model, scene.study.contact_proxy_segments);
}

ContactBranchOptions scene_contact_penalty(const Scene& scene, const ShellModel& model,
                                           const ContactProxy& proxy) {
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
  if (scene.study.contact_surface == SceneContactSurface::LimitSurface)
    c.gap.limit_surface = make_limit_surface_contact(model, c.exclusion_radius);
  return c;
}

NewtonOptions scene_penalty_relaxation(const Scene& scene, const ShellModel& model) {
  const double h = thickness_at_radius(scene.thickness, 0.0, scene.geometry.radius);
  NewtonOptions newton;
  newton.gradient_tolerance = scene.study.tolerance * model.natural_force_scale();
  newton.decrement_tolerance = 1e-6 * scene.material.youngs_modulus * h * h * h;
  newton.max_iterations = 400;
  return newton;
}

}  // namespace growshell
