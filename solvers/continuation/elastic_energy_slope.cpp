#include "solvers/continuation/elastic_energy_slope.hpp"

namespace growshell {

double elastic_energy_slope(const ShellModel& model, const Eigen::Ref<const Eigen::VectorXd>& x,
                            double phi, double delta) {
  const ShellEnergyBreakdown up = model.energy_breakdown(x, phi + delta);
  const ShellEnergyBreakdown down = model.energy_breakdown(x, phi - delta);
  return ((up.stretching + up.bending) - (down.stretching + down.bending)) / (2.0 * delta);
}

}  // namespace growshell
