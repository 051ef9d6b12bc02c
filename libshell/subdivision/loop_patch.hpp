#pragma once
/// \file
/// The control points of one Loop element and the exact evaluation of its basis functions,
/// at regular and at extraordinary corners.
///
/// An element is a control-mesh face (a, b, c) whose three corners are interior vertices.
/// Its limit surface over the parameter triangle {v >= 0, w >= 0, v + w <= 1} (a at u = 1 - v - w
/// = 1, b at v = 1, c at w = 1) depends on the vertices of the faces around its corners:
///   x(v, w) = sum_i N_i(v, w) x_i.
/// If all three corners have valence 6 (and their one-rings do not overlap) these are the 12
/// box-spline functions of loop_basis.hpp.
/// Otherwise the faces around the element are subdivided until the point lies in a sub-triangle
/// with three valence-6 corners, which is then a regular patch (Stam 1998 evaluates the same
/// limit through the eigenbasis of the subdivision matrix; subdividing to the point is exact as
/// well and needs no tabulated eigenvectors, and works for several extraordinary corners and for
/// the ghost layer of a free edge). A point at distance d from an extraordinary corner takes
/// about log2(1/d) steps; points of a quadrature rule take a few.

#include <Eigen/Core>
#include <array>
#include <vector>

namespace growshell {

/// The control points of one element and, for an element with an extraordinary corner, the
/// faces around it.
struct LoopPatch {
  /// Control-mesh vertex indices. Regular element: the 12 nodes in the order of loop_basis.hpp
  /// (corners at local 3, 6, 7). Otherwise the corners a, b, c first (local 0, 1, 2), then the
  /// other vertices of the faces around them in order of first appearance.
  std::vector<int> control;
  /// Irregular element only: the faces around its corners, in local indices into `control`
  /// (counter-clockwise). Empty for a regular element.
  std::vector<std::array<int, 3>> faces;
  /// Local indices of the corners a (u = 1), b (v = 1), c (w = 1).
  std::array<int, 3> corners = {3, 6, 7};

  bool is_regular() const { return faces.empty(); }
  int size() const { return static_cast<int>(control.size()); }
};

/// Values and parametric derivatives of a patch's basis functions at one point: one row per
/// control point of the patch. Columns of `first`: d/dv, d/dw; of `second`: d2/dv2, d2/dw2,
/// d2/dvdw.
struct PatchBasis {
  Eigen::VectorXd value;
  Eigen::MatrixX2d first;
  Eigen::MatrixX3d second;
};

/// The basis of `patch` at (v, w) of its parameter triangle (v, w >= 0, v + w <= 1, to within
/// 1e-12). Exact to rounding. At an extraordinary corner itself the value is Loop's limit
/// position mask; the parametric derivatives there are degenerate (they scale like
/// (2 lambda)^k at distance 2^-k, lambda from loop_subdominant_eigenvalue), and those returned
/// are the ones at distance 2^-30 from the corner towards the element's centroid. Throws
/// std::invalid_argument for a point outside the triangle and std::logic_error if the patch's
/// faces do not surround its corners.
PatchBasis evaluate_patch_basis(const LoopPatch& patch, double v, double w);

/// As evaluate_patch_basis, but subdivides at least `levels` times before evaluating a regular
/// sub-patch, also for a regular element (given its faces): the same limit surface reached by
/// another route, which the tests use to check the subdivision machinery against the
/// box-spline.
PatchBasis evaluate_patch_basis_subdividing(const LoopPatch& patch, double v, double w,
                                            int levels);

/// The 12 nodes of a regular patch (order of loop_basis.hpp) from the counter-clockwise rings of
/// its corners a, b, c, each starting at the next corner: ring_a = (b, c, ...), ring_b =
/// (c, a, ...), ring_c = (a, b, ...), six entries each. Returns false (and leaves `nodes`
/// unspecified) if the rings disagree about a shared node or the 12 nodes are not distinct (the
/// rings overlap, e.g. next to a vertex of valence 3, or on a tiny closed mesh): the face is
/// then no regular patch, though its corners have valence 6.
bool regular_patch_nodes(const std::array<int, 6>& ring_a, const std::array<int, 6>& ring_b,
                         const std::array<int, 6>& ring_c, std::array<int, 12>& nodes);

}  // namespace growshell
