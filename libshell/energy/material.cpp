#include "libshell/energy/material.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace growshell {

void validate_material(const Material& material) {
  if (!(std::isfinite(material.youngs_modulus) && material.youngs_modulus > 0.0)) {
    std::ostringstream msg;
    msg << "youngs_modulus = " << material.youngs_modulus << " must be finite and > 0";
    throw std::invalid_argument(msg.str());
  }
  if (!(material.poisson_ratio > -1.0 && material.poisson_ratio < 0.5)) {
    std::ostringstream msg;
    msg << "poisson_ratio = " << material.poisson_ratio << " must lie in (-1, 0.5)";
    throw std::invalid_argument(msg.str());
  }
}

double stretching_modulus(const Material& material, double thickness) {
  const double nu = material.poisson_ratio;
  return material.youngs_modulus * thickness / (2.0 * (1.0 - nu * nu));
}

double bending_modulus(const Material& material, double thickness) {
  const double nu = material.poisson_ratio;
  return material.youngs_modulus * thickness * thickness * thickness / (24.0 * (1.0 - nu * nu));
}

}  // namespace growshell
