#include "studies/econe_winding_options.hpp"

#include <algorithm>

#include "studies/scene_contact_penalty.hpp"

namespace growshell {

ContactGrowthOptions econe_winding_options(const Scene& scene, const ShellModel& model,
                                           const ContactProxy& proxy) {
  const double h = thickness_at_radius(scene.thickness, 0.0, scene.geometry.radius);
  ContactGrowthOptions growth;
  growth.contact = scene_contact_penalty(scene, proxy);
  growth.contact.symmetric_subspace = nullptr;
  // Every triangle near a proxy vertex, not only the nearest: as the sheet winds, layers slide
  // over layers, and a vertex between two of them must be held by both.
  growth.contact.selection = NearPairSelection{false, false};
  growth.newton.gradient_tolerance = scene.study.tolerance * model.natural_force_scale();
  // The decrement test stops Newton's crawl along the nearly free turn of the fold pattern.
  growth.newton.decrement_tolerance = 1e-6 * scene.material.youngs_modulus * h * h * h;
  // Steps bounded to h/4 per dof: where a stable state ends the sheet slides a long way (layers
  // over layers) to the next one, and unbounded Newton steps push vertices through a layer.
  growth.newton.max_step_inf_norm = 0.25 * h;
  growth.newton.max_iterations = 5000;
  // Newton on the penalty's kinks: a step the line search cut short raises the next shift
  // (docs/performance.md, "The winding at h = 0.02").
  growth.newton.adaptive_shift = true;
  growth.max_step = std::min(0.05, scene.continuation.max_step);
  return growth;
}

}  // namespace growshell
