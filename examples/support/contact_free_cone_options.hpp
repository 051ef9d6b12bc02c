#pragma once
// Settings of the contact-free cone from flat (solvers/contact/contact_free_cone.hpp), shared
// by trace_contact's first stage and crit_vs_h --phi-contact-start.

#include "libshell/assembly/shell_model.hpp"
#include "libshell/io/scene.hpp"
#include "solvers/contact/contact_free_cone.hpp"

namespace growshell::examples {

/// The scene's n = 2 cone traced up to phi_contact_start: steps from the scene's continuation
/// settings, the force tolerance relative to the model's natural force scale, the scene's
/// contact distance and exclusion radius. min_step is 1e-6 as in the traces with contact, so
/// that the trace passes the symmetric cone's branch point (the scene's 1e-4 stalls there at
/// h = 0.04).
inline ContactFreeConeOptions contact_free_cone_options(const Scene& scene,
                                                        const ShellModel& model,
                                                        double tolerance,
                                                        double phi_contact_start) {
  const double R = scene.geometry.radius;
  const double h = thickness_at_radius(scene.thickness, 0.0, R);
  ContactFreeConeOptions o;
  o.arclength.initial_step = scene.continuation.max_step / 4;
  o.arclength.max_step = scene.continuation.max_step;
  o.arclength.min_step = 1e-6;
  o.arclength.gradient_tolerance = tolerance * model.natural_force_scale();
  o.arclength.parameter_max = phi_contact_start;
  o.entry.folds = 2;
  o.entry.thickness = h;
  o.entry.radius = R;
  o.contact_distance = scene.physics.contact_distance.value_or(h);
  o.exclusion_radius = resolved_exclusion_radius(scene);
  return o;
}

}  // namespace growshell::examples
