#include "studies/econe_winding_options.hpp"

#include <algorithm>
#include <fstream>
#include <stdexcept>

#include "studies/scene_contact_penalty.hpp"

namespace growshell {

ContactGrowthOptions econe_winding_options(const Scene& scene, const ShellModel& model,
                                           const ContactProxy& proxy) {
  const double h = thickness_at_radius(scene.thickness, 0.0, scene.geometry.radius);
  ContactGrowthOptions growth;
  growth.contact = scene_contact_penalty(scene, model, proxy);
  growth.contact.symmetric_subspace = nullptr;
  // Every triangle near a proxy vertex, not only the nearest: as the sheet winds, layers slide
  // over layers, and a vertex between two of them must be held by both.
  growth.contact.selection = NearPairSelection{false, false};
  growth.newton = scene_penalty_relaxation(scene, model);
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

std::vector<Eigen::Index> read_winding_pins(const std::string& path, Eigen::Index n) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot be read (the winding's pins)");
  std::vector<Eigen::Index> pins;
  long long dof = 0;
  while (in >> dof) {
    if (dof < 0 || dof >= n) throw std::runtime_error(path + ": dof " + std::to_string(dof) +
                                                      " is not in [0, " + std::to_string(n) + ")");
    pins.push_back(static_cast<Eigen::Index>(dof));
  }
  if (!in.eof() || pins.empty()) throw std::runtime_error(path + ": not a list of dofs");
  return pins;
}

}  // namespace growshell
