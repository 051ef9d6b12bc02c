#include "libshell/subdivision/triangle_quadrature.hpp"

#include <stdexcept>
#include <string>

namespace growshell {
namespace {

/// Appends the orbit of barycentric point (a, a, 1 - 2a) (three points) with area-normalised
/// weight `weight` (weights of a rule sum to 1 before the factor 1/2).
void add_orbit3(std::vector<TriangleQuadraturePoint>& rule, double a, double weight) {
  const double b = 1.0 - 2.0 * a;
  rule.push_back({a, a, 0.5 * weight});
  rule.push_back({b, a, 0.5 * weight});
  rule.push_back({a, b, 0.5 * weight});
}

/// Appends the orbit of barycentric point (a, b, 1 - a - b), all different (six points).
void add_orbit6(std::vector<TriangleQuadraturePoint>& rule, double a, double b, double weight) {
  const double c = 1.0 - a - b;
  const double p[6][2] = {{a, b}, {b, a}, {a, c}, {c, a}, {b, c}, {c, b}};
  for (const auto& q : p) rule.push_back({q[0], q[1], 0.5 * weight});
}

}  // namespace

std::vector<TriangleQuadraturePoint> triangle_quadrature(int degree) {
  std::vector<TriangleQuadraturePoint> rule;
  switch (degree) {
    case 1:
      rule.push_back({1.0 / 3.0, 1.0 / 3.0, 0.5});
      break;
    case 2:
      add_orbit3(rule, 1.0 / 6.0, 1.0 / 3.0);
      break;
    case 3:
    case 4:
      add_orbit3(rule, 0.445948490915965, 0.223381589678011);
      add_orbit3(rule, 0.091576213509771, 0.109951743655322);
      break;
    case 5:
      rule.push_back({1.0 / 3.0, 1.0 / 3.0, 0.5 * 0.225});
      add_orbit3(rule, 0.470142064105115, 0.132394152788506);
      add_orbit3(rule, 0.101286507323456, 0.125939180544827);
      break;
    case 6:
      add_orbit3(rule, 0.249286745170910, 0.116786275726379);
      add_orbit3(rule, 0.063089014491502, 0.050844906370207);
      add_orbit6(rule, 0.310352451033784, 0.053145049844817, 0.082851075618374);
      break;
    default:
      throw std::invalid_argument("quadrature degree " + std::to_string(degree) +
                                  " is not available; allowed: 1, 2, 3, 4, 5, 6");
  }
  return rule;
}

}  // namespace growshell
