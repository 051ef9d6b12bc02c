#include "libshell/analysis/core_radius.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace growshell {

double element_reference_radius(const ShellModel& model, Eigen::Index e, const Eigen::Vector3d& center) {
  const Eigen::VectorXd& X = model.reference_positions();
  const std::array<int, 3>& f = model.topology().face(model.patches().face[static_cast<std::size_t>(e)]);
  const Eigen::Vector3d centroid =
      (X.segment<3>(3 * f[0]) + X.segment<3>(3 * f[1]) + X.segment<3>(3 * f[2])) / 3.0;
  return (centroid - center).head<2>().norm();
}

CoreRadius stretching_core_radius(const ShellModel& model, const Eigen::Ref<const Eigen::VectorXd>& x,
                                  double excess_angle, double fraction,
                                  const Eigen::Vector3d& center) {
  if (!(fraction > 0.0 && fraction < 1.0))
    throw std::invalid_argument("stretching_core_radius: fraction = " + std::to_string(fraction) +
                                " must be in (0, 1)");
  if (x.size() != model.dimension())
    throw std::invalid_argument("stretching_core_radius: x has " + std::to_string(x.size()) +
                                " entries, expected " + std::to_string(model.dimension()));
  std::vector<std::pair<double, double>> radius_energy(static_cast<std::size_t>(model.num_elements()));
  double total = 0.0;
  for (Eigen::Index e = 0; e < model.num_elements(); ++e) {
    const double energy = model.element_breakdown(x, excess_angle, e).stretching;
    radius_energy[static_cast<std::size_t>(e)] = {element_reference_radius(model, e, center), energy};
    total += energy;
  }
  if (!(total > 0.0))
    throw std::invalid_argument("stretching_core_radius: the stretching energy is " +
                                std::to_string(total) + " (no stretched core to measure)");
  std::sort(radius_energy.begin(), radius_energy.end());
  const double target = fraction * total;
  double below = 0.0, previous_radius = 0.0;
  CoreRadius out;
  out.stretching_energy = total;
  out.radius = radius_energy.back().first;
  for (const auto& [radius, energy] : radius_energy) {
    if (below + energy >= target) {
      // The cumulative energy rises from `below` at previous_radius to below + energy here.
      const double t = energy > 0.0 ? (target - below) / energy : 1.0;
      out.radius = previous_radius + t * (radius - previous_radius);
      break;
    }
    below += energy;
    previous_radius = radius;
  }
  return out;
}

}  // namespace growshell
