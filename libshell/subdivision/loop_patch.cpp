#include "libshell/subdivision/loop_patch.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "libshell/subdivision/local_loop_subdivision.hpp"
#include "libshell/subdivision/loop_basis.hpp"
#include "libshell/subdivision/loop_rules.hpp"

namespace growshell {
namespace {

// A point of the parameter triangle closer than 2^-kCornerLevels to an extraordinary corner is
// evaluated there by the limit mask (value) and at that distance (derivatives).
constexpr int kCornerLevels = 30;
// Subdivision steps after which a point must have reached a regular sub-patch.
constexpr int kMaxLevels = kCornerLevels + 8;

// The current sub-triangle: a face of `mesh`, the point's barycentric coordinates in it, and the
// parameter positions (v, w) of its corners in the element's own parameter triangle.
struct SubPatch {
  LocalLoopMesh mesh;
  Eigen::MatrixXd to_control;  // mesh vertex -> weights of the patch's control points
  std::array<int, 3> triangle;
  Eigen::Vector3d barycentric;
  std::array<Eigen::Vector2d, 3> corner_parameter;
};

std::array<int, 6> ring_starting_at(const LocalFan& fan, int first) {
  const auto it = std::find(fan.neighbours.begin(), fan.neighbours.end(), first);
  if (it == fan.neighbours.end())
    throw std::logic_error("Loop patch: a corner of the sub-triangle is not in its neighbour's ring");
  const auto start = static_cast<std::size_t>(it - fan.neighbours.begin());
  std::array<int, 6> ring{};
  for (std::size_t k = 0; k < 6; ++k) ring[k] = fan.neighbours[(start + k) % 6];
  return ring;
}

// The 12 nodes of `triangle` if its corners have closed valence-6 fans in `mesh` and their
// one-rings form the regular 12-node configuration (next to a vertex of low valence they can
// overlap; one more step separates them).
bool regular_sub_patch(const LocalLoopMesh& mesh, const std::array<int, 3>& triangle,
                       std::array<int, 12>& nodes) {
  std::array<std::array<int, 6>, 3> rings;
  for (int k = 0; k < 3; ++k) {
    LocalFan fan;
    try {
      fan = local_fan(mesh, triangle[static_cast<std::size_t>(k)]);
    } catch (const std::invalid_argument&) {
      return false;  // the kept faces meet at this corner from two sides: refine further
    }
    if (!fan.closed || fan.neighbours.size() != 6) return false;
    rings[static_cast<std::size_t>(k)] = ring_starting_at(fan, triangle[static_cast<std::size_t>((k + 1) % 3)]);
  }
  return regular_patch_nodes(rings[0], rings[1], rings[2], nodes);
}

// Index f of the face of `mesh` that is `triangle` up to rotation, and that rotation r:
// faces[f][(r + k) % 3] == triangle[k].
std::pair<std::size_t, int> find_face(const LocalLoopMesh& mesh, const std::array<int, 3>& triangle) {
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (int r = 0; r < 3; ++r)
      if (mesh.faces[f][static_cast<std::size_t>(r)] == triangle[0] &&
          mesh.faces[f][static_cast<std::size_t>((r + 1) % 3)] == triangle[1] &&
          mesh.faces[f][static_cast<std::size_t>((r + 2) % 3)] == triangle[2])
        return {f, r};
  throw std::logic_error("Loop patch: the element is not a face of its own patch");
}

// One subdivision step, keeping only the faces around the sub-triangle that holds the point.
SubPatch refine_towards_point(const SubPatch& coarse) {
  const LocalSubdivisionStep step = subdivide_local_mesh(coarse.mesh);
  // Named copies, not a structured binding: clang before 16 cannot capture bindings.
  const std::pair<std::size_t, int> found = find_face(coarse.mesh, coarse.triangle);
  const std::size_t f = found.first;
  const int r = found.second;
  const auto edge = [&](int k) { return step.edge_point[f][static_cast<std::size_t>((r + k) % 3)]; };
  const int a = coarse.triangle[0], b = coarse.triangle[1], c = coarse.triangle[2];
  const int ab = edge(0), bc = edge(1), ca = edge(2);
  const double u = coarse.barycentric[0], v = coarse.barycentric[1], w = coarse.barycentric[2];
  const auto& P = coarse.corner_parameter;
  const Eigen::Vector2d Pab = 0.5 * (P[0] + P[1]), Pbc = 0.5 * (P[1] + P[2]), Pca = 0.5 * (P[2] + P[0]);
  SubPatch fine;
  if (u >= 0.5) {
    fine.triangle = {a, ab, ca};
    fine.barycentric = {2 * u - 1, 2 * v, 2 * w};
    fine.corner_parameter = {P[0], Pab, Pca};
  } else if (v >= 0.5) {
    fine.triangle = {ab, b, bc};
    fine.barycentric = {2 * u, 2 * v - 1, 2 * w};
    fine.corner_parameter = {Pab, P[1], Pbc};
  } else if (w >= 0.5) {
    fine.triangle = {ca, bc, c};
    fine.barycentric = {2 * u, 2 * v, 2 * w - 1};
    fine.corner_parameter = {Pca, Pbc, P[2]};
  } else {
    fine.triangle = {bc, ca, ab};
    fine.barycentric = {1 - 2 * u, 1 - 2 * v, 1 - 2 * w};
    fine.corner_parameter = {Pbc, Pca, Pab};
  }
  fine.barycentric = fine.barycentric.cwiseMax(0.0);
  fine.barycentric /= fine.barycentric.sum();

  // Keep the faces around the new triangle's corners: they hold its one-ring, and every vertex
  // of theirs that the next step needs is computable (its rule only sees faces around a corner
  // of the coarse triangle, which the coarse patch kept).
  std::vector<int> local(static_cast<std::size_t>(step.refined.num_vertices), -1);
  std::vector<int> kept;
  for (const auto& face : step.refined.faces) {
    const bool around = std::any_of(face.begin(), face.end(), [&](int x) {
      return x == fine.triangle[0] || x == fine.triangle[1] || x == fine.triangle[2];
    });
    if (!around) continue;
    std::array<int, 3> renumbered{};
    for (std::size_t k = 0; k < 3; ++k) {
      int& slot = local[static_cast<std::size_t>(face[k])];
      if (slot < 0) {
        if (!step.computable[static_cast<std::size_t>(face[k])])
          throw std::logic_error("Loop patch: the faces around the element do not surround its corners");
        slot = static_cast<int>(kept.size());
        kept.push_back(face[k]);
      }
      renumbered[k] = slot;
    }
    fine.mesh.faces.push_back(renumbered);
  }
  fine.mesh.num_vertices = static_cast<int>(kept.size());
  for (auto& corner : fine.triangle) corner = local[static_cast<std::size_t>(corner)];
  fine.to_control.resize(fine.mesh.num_vertices, coarse.to_control.cols());
  for (std::size_t k = 0; k < kept.size(); ++k)
    fine.to_control.row(static_cast<Eigen::Index>(k)) =
        step.rule.row(kept[k]) * coarse.to_control;
  return fine;
}

// The regular basis of the sub-patch `nodes` at the sub-triangle point, carried back to the
// element's control points and parameters.
PatchBasis regular_basis_in_element(const SubPatch& s, const std::array<int, 12>& nodes) {
  const LoopBasisValues b = evaluate_regular_loop_basis(s.barycentric[1], s.barycentric[2]);
  const auto& P = s.corner_parameter;
  Eigen::Matrix2d M;  // d(v, w)/d(v', w')
  M << P[1] - P[0], P[2] - P[0];
  const Eigen::Matrix2d Minv = M.inverse();
  Eigen::Matrix<double, 12, Eigen::Dynamic> gather(12, s.to_control.cols());
  for (int k = 0; k < 12; ++k) gather.row(k) = s.to_control.row(nodes[static_cast<std::size_t>(k)]);
  PatchBasis out;
  out.value = gather.transpose() * b.value;
  out.first = gather.transpose() * (b.first * Minv);
  Eigen::Matrix<double, 12, 3> second;
  for (int k = 0; k < 12; ++k) {
    Eigen::Matrix2d H;
    H << b.second(k, 0), b.second(k, 2), b.second(k, 2), b.second(k, 1);
    const Eigen::Matrix2d Ho = Minv.transpose() * H * Minv;
    second.row(k) << Ho(0, 0), Ho(1, 1), Ho(0, 1);
  }
  out.second = gather.transpose() * second;
  return out;
}

void check_point(double v, double w) {
  constexpr double slack = 1e-12;
  if (!(std::isfinite(v) && std::isfinite(w) && v >= -slack && w >= -slack && v + w <= 1 + slack)) {
    std::ostringstream msg;
    msg << "Loop patch: (v, w) = (" << v << ", " << w << ") is outside the parameter triangle";
    throw std::invalid_argument(msg.str());
  }
}

PatchBasis evaluate_by_subdivision(const LoopPatch& patch, double v, double w, int min_levels) {
  SubPatch s;
  s.mesh.num_vertices = patch.size();
  s.mesh.faces = patch.faces;
  s.to_control = Eigen::MatrixXd::Identity(patch.size(), patch.size());
  s.triangle = patch.corners;
  s.barycentric = Eigen::Vector3d(1.0 - v - w, v, w).cwiseMax(0.0);
  s.barycentric /= s.barycentric.sum();
  s.corner_parameter = {Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 0), Eigen::Vector2d(0, 1)};
  for (int level = 0; level <= kMaxLevels; ++level) {
    std::array<int, 12> nodes{};
    if (level >= min_levels && regular_sub_patch(s.mesh, s.triangle, nodes))
      return regular_basis_in_element(s, nodes);
    s = refine_towards_point(s);
  }
  throw std::logic_error("Loop patch: no regular sub-patch reached");
}

}  // namespace

bool regular_patch_nodes(const std::array<int, 6>& ra, const std::array<int, 6>& rb,
                         const std::array<int, 6>& rc, std::array<int, 12>& nodes) {
  // ra = (b, c, n4, n1, n0, n2), rb = (c, a, n2, n5, n9, n10), rc = (a, b, n10, n11, n8, n4)
  // in the 0-based node numbering of loop_basis.hpp (a = n3, b = n6, c = n7).
  if (ra[1] != rb[0] || rb[1] != rc[0] || rc[1] != ra[0]) return false;
  if (ra[5] != rb[2] || rb[5] != rc[2] || rc[5] != ra[2]) return false;
  nodes = {ra[4], ra[3], ra[5], rc[0], ra[2], rb[3], ra[0], rb[0], rc[4], rb[4], rb[5], rc[3]};
  std::array<int, 12> sorted = nodes;
  std::sort(sorted.begin(), sorted.end());
  return std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end();
}

PatchBasis evaluate_patch_basis(const LoopPatch& patch, double v, double w) {
  check_point(v, w);
  if (patch.is_regular()) {
    if (patch.size() != 12) throw std::logic_error("Loop patch: a regular patch has 12 nodes");
    const LoopBasisValues b = evaluate_regular_loop_basis(v, w);
    return {b.value, b.first, b.second};
  }
  const Eigen::Vector3d barycentric(1.0 - v - w, v, w);
  Eigen::Index corner = 0;
  const double nearest = barycentric.maxCoeff(&corner);
  const double distance = 1.0 - nearest;
  if (distance < std::ldexp(1.0, -kCornerLevels)) {
    const LocalLoopMesh mesh{patch.size(), patch.faces};
    const int vertex = patch.corners[static_cast<std::size_t>(corner)];
    const LocalFan fan = local_fan(mesh, vertex);
    const int valence = static_cast<int>(fan.neighbours.size());
    if (fan.closed && valence != 6) {
      // Extraordinary corner: exact limit position, derivatives just inside the element.
      const double t = 1.5 * std::ldexp(1.0, -kCornerLevels);
      Eigen::Vector3d inside = (1.0 - t) * Eigen::Vector3d::Unit(corner) + t * Eigen::Vector3d::Constant(1.0 / 3.0);
      PatchBasis out = evaluate_by_subdivision(patch, inside[1], inside[2], 0);
      const double chi = loop_limit_neighbour_weight(valence);
      out.value.setZero();
      out.value[vertex] = 1.0 - valence * chi;
      for (int u : fan.neighbours) out.value[u] += chi;
      return out;
    }
  }
  return evaluate_by_subdivision(patch, v, w, 0);
}

PatchBasis evaluate_patch_basis_subdividing(const LoopPatch& patch, double v, double w, int levels) {
  check_point(v, w);
  if (patch.faces.empty())
    throw std::invalid_argument("evaluate_patch_basis_subdividing: the patch carries no faces");
  if (levels < 0 || levels > kMaxLevels)
    throw std::invalid_argument("evaluate_patch_basis_subdividing: levels must be in [0, " +
                                std::to_string(kMaxLevels) + "]");
  return evaluate_by_subdivision(patch, v, w, levels);
}

}  // namespace growshell
