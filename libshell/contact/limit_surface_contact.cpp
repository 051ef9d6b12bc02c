#include "libshell/contact/limit_surface_contact.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "libshell/subdivision/element_neighbourhood.hpp"

namespace growshell {

std::shared_ptr<const LimitSurfaceContact> make_limit_surface_contact(const ShellModel& model,
                                                                      double exclusion_radius) {
  if (!std::isfinite(exclusion_radius) || exclusion_radius < 0.0)
    throw std::invalid_argument("make_limit_surface_contact: the exclusion radius " +
                                std::to_string(exclusion_radius) + " must be finite and >= 0");
  auto contact = std::make_shared<LimitSurfaceContact>();
  contact->exclusion_radius = exclusion_radius;
  contact->patches = model.patches();
  contact->neighbourhoods = element_neighbourhoods(model.topology(), model.patches());
  return contact;
}

}  // namespace growshell
