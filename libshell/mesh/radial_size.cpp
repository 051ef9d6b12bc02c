#include "libshell/mesh/radial_size.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "libshell/mesh/mesh_error.hpp"

namespace growshell {

double radial_size(const RadialSize& size, double r) {
  return std::min(std::max(size.slope * r, size.floor), size.max);
}

void check_radial_size(const RadialSize& size, const std::string& caller) {
  if (!(std::isfinite(size.slope) && size.slope > 0.0))
    throw MeshError(caller + ": size_slope must be finite and > 0, got " +
                    std::to_string(size.slope));
  if (!(std::isfinite(size.floor) && size.floor > 0.0))
    throw MeshError(caller + ": size_floor must be finite and > 0, got " +
                    std::to_string(size.floor));
  if (!(size.max >= size.floor))
    throw MeshError(caller + ": size_max must be >= size_floor (" + std::to_string(size.floor) +
                    "), got " + std::to_string(size.max));
}

// u(r): r / floor up to r_a = floor / slope, then u_a + ln(r / r_a) / slope up to
// r_b = max / slope, then u_b + (r - r_b) / max.
double radial_size_coordinate(const RadialSize& size, double r) {
  const double ra = size.floor / size.slope;
  if (r <= ra) return r / size.floor;
  const double ua = ra / size.floor;
  const double rb = size.max / size.slope;  // +inf without a cap
  if (r <= rb) return ua + std::log(r / ra) / size.slope;
  const double ub = ua + std::log(rb / ra) / size.slope;
  return ub + (r - rb) / size.max;
}

double radius_at_size_coordinate(const RadialSize& size, double u) {
  const double ra = size.floor / size.slope;
  const double ua = ra / size.floor;  // = 1 / slope
  if (u <= ua) return u * size.floor;
  const double rb = size.max / size.slope;
  const double ub = std::isfinite(rb) ? ua + std::log(rb / ra) / size.slope
                                      : std::numeric_limits<double>::infinity();
  if (u <= ub) return ra * std::exp(size.slope * (u - ua));
  return rb + (u - ub) * size.max;
}

}  // namespace growshell
