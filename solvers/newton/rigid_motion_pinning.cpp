#include "solvers/newton/rigid_motion_pinning.hpp"

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace growshell {
namespace {

// Below this ratio of the best triangle area to |B - A|^2 / 2 the third pin would control
// the rotation about AB only through a near-zero lever arm.
constexpr double kCollinearityTolerance = 1e-6;

int dominant_component(const Eigen::Vector3d& v) {
  int k = 0;
  v.cwiseAbs().maxCoeff(&k);
  return k;
}

}  // namespace

std::vector<Eigen::Index> rigid_motion_pinned_dofs(
    const Eigen::Ref<const Eigen::MatrixX3d>& positions,
    const std::vector<int>& candidate_vertices) {
  if (candidate_vertices.size() < 3) {
    throw std::invalid_argument(
        "rigid_motion_pinned_dofs: need at least 3 candidate vertices, got " +
        std::to_string(candidate_vertices.size()));
  }
  for (const int v : candidate_vertices) {
    if (v < 0 || v >= positions.rows()) {
      throw std::invalid_argument("rigid_motion_pinned_dofs: candidate vertex " +
                                  std::to_string(v) + " is out of range [0, " +
                                  std::to_string(positions.rows()) + ")");
    }
    if (!positions.row(v).allFinite()) {
      throw std::invalid_argument("rigid_motion_pinned_dofs: candidate vertex " +
                                  std::to_string(v) + " has a non-finite position");
    }
  }
  const int a = candidate_vertices.front();
  const Eigen::Vector3d pa = positions.row(a).transpose();

  int b = a;
  double best_distance = 0.0;
  for (const int v : candidate_vertices) {
    const double d = (positions.row(v).transpose() - pa).squaredNorm();
    if (d > best_distance) {
      best_distance = d;
      b = v;
    }
  }
  const Eigen::Vector3d ab = positions.row(b).transpose() - pa;

  int c = a;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  for (const int v : candidate_vertices) {
    const Eigen::Vector3d n = ab.cross(positions.row(v).transpose() - pa);
    if (n.squaredNorm() > normal.squaredNorm()) {
      normal = n;
      c = v;
    }
  }
  if (!(normal.norm() > kCollinearityTolerance * ab.squaredNorm()) || best_distance == 0.0) {
    throw std::invalid_argument(
        "rigid_motion_pinned_dofs: the " + std::to_string(candidate_vertices.size()) +
        " candidate vertices are (nearly) collinear (largest |(B-A)x(C-A)| = " +
        std::to_string(normal.norm()) + " with |B-A|^2 = " + std::to_string(ab.squaredNorm()) +
        "); rotations about their line cannot be removed");
  }

  // With A fixed, a rigid velocity is w x (p - A). Zeroing the two components of w x (B - A)
  // transverse to its dominant axis forces w parallel to B - A (w x (B - A) is orthogonal to
  // B - A); the remaining spin about AB moves C along the normal, so pinning C's dominant
  // normal component removes it.
  const int kb = dominant_component(ab);
  const int kc = dominant_component(normal);
  std::vector<Eigen::Index> dofs;
  dofs.reserve(6);
  for (int k = 0; k < 3; ++k) dofs.push_back(3 * static_cast<Eigen::Index>(a) + k);
  for (int k = 0; k < 3; ++k) {
    if (k != kb) dofs.push_back(3 * static_cast<Eigen::Index>(b) + k);
  }
  dofs.push_back(3 * static_cast<Eigen::Index>(c) + kc);
  return dofs;
}

}  // namespace growshell

namespace growshell {

std::vector<Eigen::Index> mirror_axis_pinned_dofs(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                                                  const std::vector<int>& sheet_vertices,
                                                  const Eigen::Vector3d& center) {
  if (sheet_vertices.empty())
    throw std::invalid_argument("mirror_axis_pinned_dofs: no sheet vertices");
  int nearest = sheet_vertices.front(), along_x = nearest, along_y = nearest;
  const auto offset = [&](int v) { return (positions.row(v).transpose() - center).eval(); };
  for (int v : sheet_vertices) {
    if (offset(v).head<2>().norm() < offset(nearest).head<2>().norm()) nearest = v;
    if (offset(v).x() > offset(along_x).x()) along_x = v;
    if (offset(v).y() > offset(along_y).y()) along_y = v;
  }
  return rigid_motion_pinned_dofs(positions, {nearest, along_x, along_y});
}

}  // namespace growshell

namespace growshell {

double pinned_rigid_motion_condition(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                                     const std::vector<Eigen::Index>& dofs) {
  if (dofs.size() != 6)
    throw std::invalid_argument("pinned_rigid_motion_condition: need 6 dofs, got " +
                                std::to_string(dofs.size()));
  for (const Eigen::Index d : dofs)
    if (d < 0 || d >= 3 * positions.rows())
      throw std::invalid_argument("pinned_rigid_motion_condition: dof " + std::to_string(d) +
                                  " is out of range [0, " + std::to_string(3 * positions.rows()) +
                                  ")");
  const Eigen::RowVector3d centroid = positions.colwise().mean();
  const double scale = std::sqrt((positions.rowwise() - centroid).rowwise().squaredNorm().mean());
  if (!(scale > 0.0)) return std::numeric_limits<double>::infinity();
  Eigen::Matrix<double, 6, 6> m;
  for (int r = 0; r < 6; ++r) {
    const Eigen::Index v = dofs[static_cast<std::size_t>(r)] / 3;
    const int c = static_cast<int>(dofs[static_cast<std::size_t>(r)] % 3);
    const Eigen::Vector3d p = (positions.row(v) - centroid).transpose() / scale;
    for (int k = 0; k < 3; ++k) {
      m(r, k) = c == k ? 1.0 : 0.0;
      m(r, 3 + k) = Eigen::Vector3d::Unit(k).cross(p)(c);
    }
  }
  const Eigen::JacobiSVD<Eigen::Matrix<double, 6, 6>> svd(m);
  const double smallest = svd.singularValues()(5);
  return smallest > 0.0 ? svd.singularValues()(0) / smallest
                        : std::numeric_limits<double>::infinity();
}

}  // namespace growshell

namespace growshell {

std::vector<Eigen::Index> well_conditioned_pins(const Eigen::Ref<const Eigen::MatrixX3d>& positions,
                                                const std::vector<Eigen::Index>& pins,
                                                const std::vector<int>& candidate_vertices,
                                                double max_condition) {
  if (pinned_rigid_motion_condition(positions, pins) <= max_condition) return pins;
  std::vector<int> candidates{static_cast<int>(pins.front() / 3)};
  candidates.insert(candidates.end(), candidate_vertices.begin(), candidate_vertices.end());
  return rigid_motion_pinned_dofs(positions, candidates);
}

}  // namespace growshell
