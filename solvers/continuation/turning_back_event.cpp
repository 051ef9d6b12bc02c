#include "solvers/continuation/turning_back_event.hpp"

#include <stdexcept>
#include <string>

namespace growshell {

BranchEvent turning_back_event(int direction) {
  if (direction != 1 && direction != -1)
    throw std::invalid_argument("turning_back_event: direction must be +1 or -1 (got " +
                                std::to_string(direction) + ")");
  BranchEvent event;
  event.kind = "turns_back";
  const double sign = direction;
  event.value = [sign](const BranchSample& s) { return sign * s.tangent_parameter; };
  event.stop = true;
  event.needs_tangent = true;
  return event;
}

}  // namespace growshell
