#pragma once
/// \file
/// The contact proxy: a refined piecewise-linear triangle mesh whose vertices lie exactly on
/// the Loop limit surface, so that self-contact is measured on the surface the energy sees and
/// not on the control mesh (which lies off the surface by O(spacing^2 curvature) and, for a
/// folded sheet, can touch itself where the limit surface does not, or miss real contact).
///
/// Why a fixed linear map: limit-surface positions are linear in the control points,
/// y = M x, with M depending only on the mesh and the refinement. Distances, gaps and their
/// derivatives are then computed on the proxy and pulled back by M (dg/dx = dg/dy M), which
/// keeps the contact constraints' Jacobians exact and sparse. The only approximation is the
/// proxy's sag between its vertices, which proxy_sag measures (the margin knob).

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "libshell/assembly/shell_model.hpp"

namespace growshell {

/// Piecewise-linear proxy of the limit surface of a ShellModel.
///
/// Construction (make_contact_proxy): every element e (in increasing order) is split into
/// n^2 sub-triangles on the parameter lattice (v, w) = (i / n, j / n), i, j >= 0, i + j <= n,
/// with n = segments_per_edge. Parameters as in loop_patch.hpp: (0, 0), (1, 0) and (0, 1) are the
/// corners a, b, c of the element's face. Lattice points on element corners
/// and edges are shared with the neighbouring elements and are created once (by the first
/// element that reaches them), so the proxy is a conforming, consistently oriented triangle
/// mesh with the same topology as the sheet. Counts for a sheet of V vertices, E edges and
/// F elements: V + E (n - 1) + F (n - 1)(n - 2) / 2 proxy vertices and F n^2 triangles.
///
/// Order: proxy vertices are numbered in creation order (elements in order, lattice points
/// with i outer and j inner). The triangles of element e are rows e n^2 .. (e + 1) n^2 - 1,
/// listed for i = 0..n-1 (outer), j = 0..n-1-i (inner) as the "up" triangle
/// ((i, j), (i + 1, j), (i, j + 1)) followed, if i + j < n - 1, by the "down" triangle
/// ((i + 1, j), (i + 1, j + 1), (i, j + 1)). Both are counter-clockwise in (v, w), so the
/// triangle normals point along the limit surface normal a_1 x a_2 (+z on a flat disc).
struct ContactProxy {
  /// Segments per element edge n (>= 1); n = 1 gives the sheet's corner vertices only.
  int segments_per_edge = 1;
  /// Limit-surface map: rows 3 p + c (proxy vertex p, coordinate c), columns the model's
  /// unknowns (3 v + c, vertex-major), dimensionless weights. Proxy positions are map * x.
  Eigen::SparseMatrix<double> map;
  /// Proxy triangles (rows of proxy vertex indices), counter-clockwise, order as above.
  Eigen::MatrixX3i triangles;
  /// Unique proxy edges (lower index, higher index), sorted lexicographically.
  Eigen::MatrixX2i edges;
  /// Proxy vertices on the reference limit surface (map * model.reference_positions(),
  /// metres, one row per proxy vertex).
  Eigen::MatrixX3d reference_positions;
  /// Element each proxy vertex was created from (the first element containing it).
  Eigen::VectorXi vertex_element;
  /// Parameter (v, w) of each proxy vertex in vertex_element.
  Eigen::MatrixX2d vertex_parameter;
  /// Element of each proxy triangle.
  Eigen::VectorXi triangle_element;

  /// Number of proxy vertices.
  Eigen::Index num_vertices() const { return reference_positions.rows(); }
};

/// Builds the proxy of the limit surface of `model` with `segments_per_edge` segments per
/// element edge (see ContactProxy). Throws std::invalid_argument naming segments_per_edge if
/// it is < 1, or above 1000 (a bound that keeps the indices far from overflow).
ContactProxy make_contact_proxy(const ShellModel& model, int segments_per_edge);

/// Where a point of an element's parameter triangle lies on the proxy.
struct ProxyTriangleLocation {
  int triangle = -1;  ///< row of ContactProxy::triangles
  /// Weights of the triangle's three corners (in its row's order) that give the point's
  /// parameter: >= 0, summing to 1.
  Eigen::Vector3d barycentric = Eigen::Vector3d::Zero();
};

/// The proxy triangle of element `element` that holds parameter (v, w) (clamped into the
/// parameter triangle), with the point's weights in it. Throws std::invalid_argument for an
/// element outside the proxy's or a non-finite parameter.
ProxyTriangleLocation proxy_triangle_at(const ContactProxy& proxy, int element,
                                        const Eigen::Ref<const Eigen::Vector2d>& parameter);

/// The same for a proxy of `segments_per_edge` segments per element edge and `triangles`
/// triangles in all.
ProxyTriangleLocation proxy_triangle_at(int segments_per_edge, Eigen::Index triangles, int element,
                                        const Eigen::Ref<const Eigen::Vector2d>& parameter);

/// Proxy vertex positions at state x (metres, one row per proxy vertex): map * x reshaped.
/// Throws std::invalid_argument if x does not have map.cols() entries.
Eigen::MatrixX3d proxy_positions(const ContactProxy& proxy,
                                 const Eigen::Ref<const Eigen::VectorXd>& x);

/// Measured deviation of the proxy from the limit surface (metres), sampled at every
/// sub-triangle's three edge midpoints and centroid: for each sample parameter (v, w), the
/// proxy point y (linear interpolation of the sub-triangle's vertices) is compared with the
/// limit-surface point x(v, w).
struct ProxySag {
  /// Largest |n . (y - x(v, w))|, n the limit normal at (v, w): the distance of the proxy
  /// point from the surface's tangent plane, i.e. its distance from the surface to first
  /// order. THE MARGIN KNOB (see proxy_sag). Zero on a flat sheet.
  double normal = 0.0;
  /// Largest |y - x(v, w)|: also counts the in-surface offset that comes from the limit
  /// parameterisation not being affine (non-zero even on a flat but non-uniform mesh), which
  /// does not move the proxy off the surface and is irrelevant for contact.
  double parametric = 0.0;
};

/// Sag of the proxy at state x (see ProxySag). For a quadratic patch the linear interpolation
/// error peaks at or near the sampled points, so the sampled maximum is an estimate, not a
/// strict bound.
///
/// The margin knob: the proxy lies within about `normal` of the limit surface, so a proxy
/// distance D between two facing parts of the sheet means a limit-surface distance within
/// D +- 2 normal. A contact formulation that requires gap >= h on the proxy should add a
/// margin of about 2 normal (or refine segments_per_edge until 2 normal is a small fraction
/// of h). The sag falls like 1 / n^2: about l^2 / (8 rho) for sub-edges of length l on a
/// surface of curvature radius rho.
///
/// `proxy` must have been made from `model`. Throws std::invalid_argument if x does not have
/// model.dimension() entries or the proxy does not match the model (column count or number
/// of triangles).
ProxySag proxy_sag(const ShellModel& model, const ContactProxy& proxy,
                   const Eigen::Ref<const Eigen::VectorXd>& x);

}  // namespace growshell
