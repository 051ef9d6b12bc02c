#pragma once
// The pressed-strip scene of the contact solver's tests: a strip bent into an arc and pressed,
// by lowering its clamped ends, onto a flat strip held below it (thickness h = 0.02 m, Y = 1e4
// Pa, nu = 0.3), in one ShellModel. The bottom strip (0.4 x 0.2 m) lies flat in z = 0 and is
// held completely; the top strip (0.6 x 0.1 m) lies over it as a circular arc of radius 1 m,
// lowest in its middle, with both ends clamped (the ghost column and the first two columns at
// each end). The load is a prescribed displacement: the clamps are lowered by `drop` below
// the arc. In the reference the two strips lie side by side 1 m apart, so the exclusion radius
// only separates points of the same strip.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/objective_at_parameter.hpp"
#include "libshell/assembly/shell_model.hpp"
#include "libshell/contact/contact_candidates.hpp"
#include "libshell/contact/contact_gap_constraints.hpp"
#include "libshell/contact/contact_proxy.hpp"
#include "libshell/contact/near_contact_pairs.hpp"
#include "libshell/mesh/disc_mesh.hpp"
#include "solvers/contact/contact_equilibrium.hpp"
#include "solvers/newton/newton_solver.hpp"
#include "support/strict_contact_solve_options.hpp"

namespace growshell::test_support {

inline StripMeshOptions strip(double length, double width, int cells_x, int cells_y) {
  StripMeshOptions o;
  o.length = length;
  o.width = width;
  o.cells_x = cells_x;
  o.cells_y = cells_y;
  return o;
}

struct TwoStrips {
  static constexpr double kPi = 3.14159265358979323846;
  static constexpr double kH = 0.02;   // thickness = contact distance (m)
  static constexpr double kRho = 1.0;  // radius of the top strip's unloaded arc (m)
  static constexpr double kMid = 0.3;  // reference x of the top strip's middle column
  static constexpr int kMidColumn = 6;
  // The bottom strip is shifted by 0.113 m in x so that its vertex columns (every 1/3 of
  // 0.05 m on the proxy) miss the top strip's middle line by >= 0.012 m: the touching pairs
  // are then the top's middle-line vertices over the interiors of bottom triangles, with no
  // ties between coincident features.
  static constexpr double kBottomShiftX = 0.113;
  static constexpr double kBottomAwayY = 1.0;  // reference distance of the strips (m)
  // Force unit of the scene: the beam estimate of the contact force is 192 EI delta / l^3 =
  // 3e-3 N for delta = 0.15 h over the free length l = 0.5 m (EI = Y W h^3 / 12).
  static constexpr double kForce = 1e-3;

  StripMeshOptions top_mesh = strip(0.6, 0.1, 12, 2);
  StripMeshOptions bottom_mesh = strip(0.4, 0.2, 8, 4);
  Eigen::Index top_vertices = 0;
  std::vector<int> top_column;  // grid column i of each top-strip vertex
  ShellModel model;
  ContactProxy proxy;
  std::vector<Eigen::Index> bottom_dofs, clamp_dofs, prop_dofs, top_dofs;

  TwoStrips() : model(mesh(), ShellModelSettings{}), proxy(make_contact_proxy(model, 3)) {
    const Eigen::Index n = model.dimension();
    for (Eigen::Index v = 0; v < n / 3; ++v) {
      const bool top = v < top_vertices;
      const int column = top ? top_column[static_cast<std::size_t>(v)] : -2;
      const bool clamped = top && (column <= 1 || column >= top_mesh.cells_x - 1);
      for (int c = 0; c < 3; ++c) {
        if (!top) bottom_dofs.push_back(3 * v + c);
        if (top) top_dofs.push_back(3 * v + c);
        if (clamped) clamp_dofs.push_back(3 * v + c);
      }
      if (top && column == kMidColumn) prop_dofs.push_back(3 * v + 2);
    }
  }

  TriangleMesh mesh() {
    const TriangleMesh a = strip_without_idle_corners(top_mesh, top_column);
    std::vector<int> bottom_column;
    const TriangleMesh b = strip_without_idle_corners(bottom_mesh, bottom_column);
    top_vertices = a.vertices.rows();
    TriangleMesh m;
    m.vertices.resize(a.vertices.rows() + b.vertices.rows(), 3);
    m.vertices << a.vertices,
        b.vertices.rowwise() + Eigen::RowVector3d(kBottomShiftX, -kBottomAwayY, 0.0);
    m.faces.resize(a.faces.rows() + b.faces.rows(), 3);
    m.faces << a.faces, (b.faces.array() + static_cast<int>(a.vertices.rows())).matrix();
    return m;
  }

  // make_strip_mesh without the ghost corners (cells_x + 1, -1) and (-1, cells_y + 1), which
  // lie in one ghost face each and in no element's control net: free they would be unknowns
  // without energy (a singular Hessian for Ipopt), fixed they have no Hessian entry (which
  // NewtonSolver rejects). `column` receives each kept vertex's grid column i.
  static TriangleMesh strip_without_idle_corners(const StripMeshOptions& o,
                                                 std::vector<int>& column) {
    const TriangleMesh full = make_strip_mesh(o);
    const int idle[2] = {strip_vertex_index(o, o.cells_x + 1, -1),
                         strip_vertex_index(o, -1, o.cells_y + 1)};
    std::vector<int> renumber(static_cast<std::size_t>(full.vertices.rows()), -1);
    TriangleMesh m;
    m.vertices.resize(full.vertices.rows() - 2, 3);
    column.clear();
    int kept = 0;
    for (int v = 0; v < full.vertices.rows(); ++v) {
      if (v == idle[0] || v == idle[1]) continue;
      renumber[static_cast<std::size_t>(v)] = kept;
      m.vertices.row(kept++) = full.vertices.row(v);
      column.push_back(v % (o.cells_x + 3) - 1);
    }
    m.faces.resize(full.faces.rows() - 2, 3);
    int f = 0;
    for (Eigen::Index k = 0; k < full.faces.rows(); ++k) {
      const Eigen::RowVector3i face = full.faces.row(k);
      if ((face.array() == idle[0]).any() || (face.array() == idle[1]).any()) continue;
      for (int c = 0; c < 3; ++c) m.faces(f, c) = renumber[static_cast<std::size_t>(face(c))];
      ++f;
    }
    return m;
  }

  std::vector<Eigen::Index> fixed() const { return joined(bottom_dofs, clamp_dofs); }
  std::vector<Eigen::Index> fixed_and_propped() const { return joined(fixed(), prop_dofs); }
  static std::vector<Eigen::Index> joined(std::vector<Eigen::Index> a,
                                          const std::vector<Eigen::Index>& b) {
    a.insert(a.end(), b.begin(), b.end());
    std::sort(a.begin(), a.end());
    return a;
  }

  // Bottom strip flat in z = 0 under the top strip; top strip on the arc whose lowest control
  // points are at z_low, with the clamped columns lowered by `drop`.
  Eigen::VectorXd state(double z_low, double drop) const {
    Eigen::VectorXd x = model.reference_positions();
    for (Eigen::Index v = 0; v < x.size() / 3; ++v) {
      if (v >= top_vertices) {
        x(3 * v + 1) += kBottomAwayY;
        continue;
      }
      const double s = x(3 * v) - kMid;
      const int column = top_column[static_cast<std::size_t>(v)];
      const bool clamped = column <= 1 || column >= top_mesh.cells_x - 1;
      x(3 * v) = kMid + kRho * std::sin(s / kRho);
      x(3 * v + 2) = z_low + kRho * (1.0 - std::cos(s / kRho)) - (clamped ? drop : 0.0);
    }
    return x;
  }

  // Equilibrium with the clamps lowered by `drop` and the top strip's middle column propped
  // (its control points held at z = z_prop): a smooth, feasible start for the contact solve.
  Eigen::VectorXd propped(double z_prop, double drop) {
    NewtonOptions o;
    o.gradient_tolerance = 1e-10 * kForce;
    ObjectiveAtParameter energy(model, 0.0);  // no growth in this scene
    const NewtonResult r =
        NewtonSolver(o).minimize(energy, state(z_prop, drop), fixed_and_propped());
    EXPECT_TRUE(r.converged()) << r.message;
    return r.x;
  }

  ContactSolveOptions options() const { return strict_contact_solve_options(kH, kForce); }

  // Lowest proxy vertex of the top strip (m). The bottom strip's proxy lies exactly in z = 0
  // (the limit surface of a flat control net), so this is the layers' distance measured on
  // the proxy.
  double top_lowest(const Eigen::VectorXd& x) const {
    const Eigen::MatrixX3d y = proxy_positions(proxy, x);
    double lowest = std::numeric_limits<double>::infinity();
    for (Eigen::Index p = 0; p < y.rows(); ++p)
      if (proxy.vertex_element(p) < top_elements()) lowest = std::min(lowest, y(p, 2));
    return lowest;
  }
  // Elements are numbered top strip first (its faces come first in the mesh).
  int top_elements() const { return 2 * top_mesh.cells_x * top_mesh.cells_y; }
};

// Smallest exact distance (mollifier off) over all pairs near_contact_pairs finds within
// `distance`, edge-edge pairs included; +infinity if there is none.
inline double closest_pair(const ContactProxy& proxy, const Eigen::VectorXd& x, double distance,
                    double exclusion_radius) {
  const ContactCandidates near = near_contact_pairs(proxy, x, distance, exclusion_radius);
  if (near.empty()) return std::numeric_limits<double>::infinity();
  ContactGapOptions plain;
  plain.mollify_edge_edge = false;
  ContactGapConstraints c(proxy, near, 0.0, x.size(), plain);
  Eigen::VectorXd d;
  c.evaluate(x, d, nullptr);
  return d.minCoeff();
}

}  // namespace growshell::test_support
