#include "studies/special_point_modes.hpp"

#include <cmath>

#include "core/objective_at_parameter.hpp"
#include "studies/pattern_rotation.hpp"

namespace growshell {

SpecialPointModes special_point_modes(const ShellModel& model, const Eigen::Ref<const Eigen::VectorXd>& x,
                                      double phi_e, const std::vector<Eigen::Index>& pinned,
                                      int count) {
  ObjectiveAtParameter energy(model, phi_e);
  EigenpairOptions options;
  options.count = count;
  SpecialPointModes out;
  out.pairs = lowest_eigenpairs(energy, x, pinned, options);
  const Eigen::VectorXd rotation = pattern_rotation(model, x, pinned);
  for (Eigen::Index k = 0; k < out.pairs.values.size(); ++k) {
    const Eigen::VectorXd v = out.pairs.vectors.col(k);
    out.orientation_overlap.push_back(std::abs(v.dot(rotation)) / (v.norm() * rotation.norm()));
  }
  return out;
}

Eigen::VectorXd displaced_along_mode(const Eigen::Ref<const Eigen::VectorXd>& x,
                                     const Eigen::Ref<const Eigen::VectorXd>& mode,
                                     double amplitude) {
  const double scale = amplitude / mode.lpNorm<Eigen::Infinity>();
  return x + scale * mode;
}

}  // namespace growshell
