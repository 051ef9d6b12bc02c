#include "solvers/continuation/elastic_energy_slope.hpp"

namespace growshell {

double elastic_energy_slope(ShellModel& model, const Eigen::Ref<const Eigen::VectorXd>& x,
                            double phi, double delta) {
  model.set_excess_angle(phi + delta);
  const ShellEnergyBreakdown up = model.energy_breakdown(x);
  model.set_excess_angle(phi - delta);
  const ShellEnergyBreakdown down = model.energy_breakdown(x);
  model.set_excess_angle(phi);
  return ((up.stretching + up.bending) - (down.stretching + down.bending)) / (2.0 * delta);
}

}  // namespace growshell
