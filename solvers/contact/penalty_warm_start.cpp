#include "solvers/contact/penalty_warm_start.hpp"

#include <cmath>
#include <stdexcept>

#include "libshell/contact/contact_gap_constraints.hpp"

namespace growshell {

ContactSolveResult penalty_warm_start(const ContactProxy& proxy, const ContactCandidates& pairs,
                                      const Eigen::Ref<const Eigen::VectorXd>& x, double offset,
                                      double stiffness) {
  if (!(std::isfinite(offset) && offset > 0.0))
    throw std::invalid_argument("penalty_warm_start: the offset must be finite and > 0");
  if (!(std::isfinite(stiffness) && stiffness >= 0.0))
    throw std::invalid_argument("penalty_warm_start: the stiffness must be finite and >= 0");
  ContactSolveResult warm;
  warm.pairs = pairs;
  warm.x = x;
  if (pairs.empty()) return warm;
  ContactGapOptions plain;
  plain.mollify_edge_edge = false;  // so that c_k = d_k - offset for every pair
  ContactGapConstraints gaps(proxy, pairs, offset, x.size(), plain);
  Eigen::VectorXd c;
  gaps.evaluate(x, c, nullptr);
  warm.forces = (stiffness * (-c.array()).max(0.0)).matrix();
  return warm;
}

}  // namespace growshell
