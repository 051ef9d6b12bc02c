#include "libshell/subdivision/loop_rules.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace growshell {
namespace {

void check_valence(int valence) {
  if (valence < 3)
    throw std::invalid_argument("Loop rules need a valence >= 3, got " + std::to_string(valence));
}

}  // namespace

double loop_subdominant_eigenvalue(int valence) {
  check_valence(valence);
  return 0.375 + 0.25 * std::cos(2.0 * std::numbers::pi / valence);
}

double loop_vertex_neighbour_weight(int valence) {
  const double lambda = loop_subdominant_eigenvalue(valence);
  return (0.625 - lambda * lambda) / valence;
}

double loop_limit_neighbour_weight(int valence) {
  return 1.0 / (valence + 3.0 / (8.0 * loop_vertex_neighbour_weight(valence)));
}

}  // namespace growshell
