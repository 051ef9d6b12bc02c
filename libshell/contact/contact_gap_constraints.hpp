#pragma once
/// \file
/// Self-contact as inequality constraints on the control points of the shell: one gap
/// c_k(x) = d_k(x) - offset >= 0 per candidate pair of the contact proxy (vertex-triangle or
/// edge-edge), d_k the Euclidean distance between the pair's primitives at the proxy positions
/// y = proxy.map * x.
///
/// Derivatives. The narrow-phase primitives give the squared distance s of the region they
/// classify at x, with gradient and Hessian in the pair's 12 proxy coordinates; the region is
/// re-classified at every evaluation and held fixed for the derivatives (as in IPC, Li et al.
/// 2020). With d = sqrt(s):
///   grad d = grad s / (2 d),   Hess d = Hess s / (2 d) - grad s grad s^T / (4 d^3),
/// and these are pulled back to x through the 12 rows of proxy.map that give the pair's four
/// proxy vertices (a constant linear map, so dc/dx = dc/dy J and d2c/dx2 = J^T d2c/dy2 J with
/// no second-derivative term of the map). Local proxy order (12 coordinates, vertex-major):
///   vertex-triangle (p, a, b, c) = (vertex, triangle corners in the proxy's order);
///   edge-edge (p0, p1, q0, q1) = (endpoints of the first edge, endpoints of the second edge).
///
/// Near-parallel edges. The edge-edge primitives never classify edges with
/// sin^2(angle) < kParallelEdgeTolerance (1e-10) as EdgeEdge (they take the endpoint region,
/// exact for parallel edges, error < 2.5e-11 min(|e0|^2, |e1|^2) in s otherwise). Close to
/// that threshold the EdgeEdge distance has a Hessian of order 1 / (|e| sin angle), large for
/// the nearly parallel edges that are common between two stacked layers of a sheet. By
/// default (ContactGapOptions::mollify_edge_edge) an edge-edge constraint is therefore
/// multiplied by the IPC mollifier m(x) in [0, 1] of edge_edge_distance.hpp,
///   c_k = m_k(x) (d_k(x) - offset),
/// with the threshold eps_x = 1e-3 |e0|^2 |e1|^2 of the REST (reference) edges, fixed for the
/// object's lifetime. m = 1 unless sin^2(angle) < about 1e-3 (angles below about 1.8 degrees
/// between edges of rest length); the sign of c_k, i.e. feasibility, is unchanged wherever
/// m > 0, and exactly parallel edges (m = 0) leave their contact to the vertex-triangle pairs,
/// which always exist between two overlapping layers. Price: the multiplier of a mollified
/// pair is the contact force divided by m (see ContactPairGeometry::mollifier). With the
/// option off, every constraint is the plain gap d_k - offset.
///
/// Zero distance (the mid-surfaces pass through each other). d = 0 makes grad s / (2 d) a
/// 0/0: the unsigned distance has a kink (a cone) there. Values are always exact
/// (c = -offset at d = 0); the derivatives use d_eff = max(d, distance_floor()), the floor being
/// 1e-9 times the mean reference edge length of the proxy. For d >= floor this is exact; below
/// it everything stays finite (at d = 0 exactly grad s = 0, so the gradient vanishes and the
/// Hessian is Hess s / (2 floor), large but finite). Such a state means the constraint is
/// already violated by the whole offset and the two layers have crossed; the unsigned
/// distance cannot say from which side they came, so a solver must not get there (keep steps
/// smaller than the offset). pair_geometry() reports it through `distance`.
///
/// Patterns. The stencil of pair k is the union of the control dofs (columns of proxy.map) in
/// the rows of its four proxy vertices, fixed at construction: the region may change during a
/// solve but the stencil does not. Row k of the Jacobian pattern is that stencil; the Hessian
/// pattern is the upper triangle of the union over pairs of stencil x stencil.
///
/// The limit surface as the second primitive (ContactGapOptions::limit_surface). A
/// vertex-triangle pair then measures the distance from the proxy vertex to the limit surface
/// of its candidate elements (limit_surface_distance.hpp): the neighbourhood of the triangle's
/// element less the vertex's neighbours on the sheet (limit_surface_contact.hpp). The distance
/// is C1 where the flat triangle's is C1 only within its regions. Its stencil is the proxy
/// vertex's control dofs and those of every candidate, and its derivatives come straight in
/// those dofs (ContactPairDistance::dof_gradient). Edge-edge pairs have no such form and are
/// refused. Of the pairs of one proxy vertex whose elements share a corner, which would
/// measure the same part of the surface twice, only the first is kept, so count() may be below
/// the number of candidate pairs. Pairs of one vertex whose elements are farther apart are all
/// kept: with every near triangle of a vertex as candidates (the winding's sets), two of them
/// on one layer can then find the same foot and hold it twice. Such a pair's geometry names the
/// proxy triangle under its foot (`second`, `vertices`, `vertex_weights`: where its force acts on
/// the proxy); its closest points are on the limit surface, so their difference equals the weighted
/// proxy vertices only to the proxy's sag. Where the derivatives are not defined (the vertex on the
/// surface, a degenerate foot, no converged search) evaluation throws std::invalid_argument
/// naming the pair instead of using the distance floor.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <span>
#include <vector>

#include "core/inequality_constraints.hpp"
#include "libshell/contact/contact_candidates.hpp"
#include "libshell/contact/contact_proxy.hpp"
#include "libshell/contact/edge_edge_distance.hpp"
#include "libshell/contact/limit_surface_contact.hpp"
#include "libshell/contact/limit_surface_distance.hpp"
#include "libshell/contact/point_triangle_distance.hpp"

namespace growshell {

/// Kind of a contact pair.
enum class ContactPairType {
  VertexTriangle,  ///< proxy vertex against proxy triangle
  EdgeEdge         ///< proxy edge against proxy edge
};

/// Name of a pair type ("VertexTriangle", "EdgeEdge"), for messages and test output.
const char* to_string(ContactPairType type);

/// Relative distance floor: derivatives use d_eff = max(d, kContactDistanceFloor * (mean
/// reference edge length of the proxy)) (see the file comment).
inline constexpr double kContactDistanceFloor = 1e-9;

/// Options of ContactGapConstraints (and ContactPenalty).
struct ContactGapOptions {
  /// Multiply each edge-edge constraint by the IPC mollifier of its edges (see the file
  /// comment). Vertex-triangle constraints are never mollified.
  bool mollify_edge_edge = true;
  /// If set, vertex-triangle pairs measure the distance to this limit surface instead of to
  /// the proxy triangle (see the file comment); it must be the proxy's model's.
  std::shared_ptr<const LimitSurfaceContact> limit_surface;
};

/// Geometry of one contact pair at a state x: what touches what, where, and along which
/// direction. Positions in metres, in the frame of the proxy (that of x).
///
/// Contact force: for the constraint multiplier lambda_k >= 0 of an active pair (c_k = 0) the
/// force on proxy vertex i of the pair is lambda_k * mollifier * vertex_weights(i) * normal
/// (N), since d distance / d y_i = vertex_weights(i) * normal; the weights sum to zero, so the
/// forces on the two primitives are equal and opposite.
struct ContactPairGeometry {
  ContactPairType type = ContactPairType::VertexTriangle;
  /// First primitive: the proxy vertex (VertexTriangle) or row of ContactProxy::edges
  /// (EdgeEdge).
  int first = -1;
  /// Second primitive: the proxy triangle (VertexTriangle) or row of ContactProxy::edges.
  int second = -1;
  /// Proxy vertices in the local order (p, a, b, c) or (p0, p1, q0, q1).
  Eigen::Vector4i vertices = Eigen::Vector4i::Constant(-1);
  /// Closest feature of the triangle at x (meaningful for VertexTriangle only).
  PointTriangleRegion point_triangle_region = PointTriangleRegion::Face;
  /// Closest feature pair at x (meaningful for EdgeEdge only).
  EdgeEdgeRegion edge_edge_region = EdgeEdgeRegion::EdgeEdge;
  /// Euclidean distance d between the primitives (m), exact (not floored).
  double distance = 0.0;
  /// d - offset (m); negative when the pair is closer than the offset.
  double gap = 0.0;
  /// Mollifier m in [0, 1] of an edge-edge pair (1 for vertex-triangle pairs and when
  /// mollification is off); the constraint value is mollifier * gap.
  double mollifier = 1.0;
  /// Closest point on the first primitive (the vertex itself, or the point on the first edge).
  Eigen::Vector3d closest_point_first = Eigen::Vector3d::Zero();
  /// Closest point on the second primitive (triangle or second edge).
  Eigen::Vector3d closest_point_second = Eigen::Vector3d::Zero();
  /// Unit vector from the second primitive towards the first:
  /// (closest_point_first - closest_point_second) / distance. If the distance is below the
  /// floor it is replaced by the triangle's normal (counter-clockwise orientation) or by the
  /// normalised cross product of the two edges; zero for parallel edges at zero distance.
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  /// Weights w_i (dimensionless) with closest_point_first - closest_point_second =
  /// sum_i w_i y_i over the pair's proxy vertices: (1, -beta_a, -beta_b, -beta_c) with the
  /// barycentric coordinates of the closest point on the triangle, or
  /// (1 - s, s, -(1 - t), -t) with the edge parameters.
  Eigen::Vector4d vertex_weights = Eigen::Vector4d::Zero();
};

/// Distance of one pair with its derivatives with respect to the pair's 12 proxy coordinates
/// (local order of the file comment), region fixed as classified at x.
struct ContactPairDistance {
  ContactPairGeometry geometry;
  /// d distance / dy (dimensionless), computed with d_eff = max(d, floor).
  Vector12d gradient = Vector12d::Zero();
  /// d2 distance / dy2 (1/m), symmetric; zero unless requested.
  Matrix12d hessian = Matrix12d::Zero();
  /// d mollifier / dy (1/m); zero for unmollified pairs and where the mollifier is 1.
  Vector12d mollifier_gradient = Vector12d::Zero();
  /// d2 mollifier / dy2 (1/m^2); zero unless requested, for unmollified pairs and where the
  /// mollifier is 1.
  Matrix12d mollifier_hessian = Matrix12d::Zero();
  /// true for a pair measured on the limit surface: its derivatives are then not in the 12
  /// proxy coordinates (gradient and hessian above stay zero) but in the control dofs
  /// pair_dofs(k), in that order, below.
  bool on_pair_dofs = false;
  Eigen::VectorXd dof_gradient;  ///< d distance / dx over pair_dofs(k) (dimensionless)
  Eigen::MatrixXd dof_hessian;   ///< d2 distance / dx2 over pair_dofs(k) (1/m), if requested
};

/// Contact gaps c_k(x) >= 0 of a fixed list of candidate pairs (see the file comment).
///
/// Constraint order: the vertex-triangle pairs (rows of ContactCandidates::vertex_triangle, in
/// order; on the limit surface without the dropped repeats) then the edge-edge pairs (rows of
/// ContactCandidates::edge_edge). Unknowns: the
/// control coordinates x of the ShellModel the proxy was made from (x[3 v + c], metres),
/// optionally followed by further unknowns that the constraints do not depend on.
///
/// The object copies what it needs from the proxy and the candidates (it keeps no reference).
/// Rebuild it with new candidates between solves, never during one. Evaluation methods are
/// const and keep no state, so they may be called concurrently.
class ContactGapConstraints final : public InequalityConstraints {
 public:
  /// Constraints of the pairs `pairs` of `proxy` with contact distance `offset` (m, e.g. the
  /// thickness h: two mid-surfaces touch at distance h), over `dimension` unknowns.
  /// Throws std::invalid_argument naming the offending item if offset is not finite or is
  /// negative, dimension < proxy.map.cols(), the proxy is inconsistent (map rows != 3 x
  /// vertices, reference_positions rows), a pair index is out of range, a vertex is a corner of
  /// its triangle, or two edges share a vertex.
  ContactGapConstraints(const ContactProxy& proxy, const ContactCandidates& pairs, double offset,
                        Eigen::Index dimension, ContactGapOptions options = {});

  Eigen::Index dimension() const override { return dimension_; }
  Eigen::Index count() const override { return static_cast<Eigen::Index>(pairs_.size()); }
  Eigen::SparseMatrix<double, Eigen::RowMajor> jacobian_pattern() const override {
    return jacobian_pattern_;
  }
  Eigen::SparseMatrix<double> hessian_pattern() const override { return hessian_pattern_; }

  /// Gaps c(x) (m) and, if `jacobian` is non-null, dc/dx (dimensionless) into a matrix that
  /// carries jacobian_pattern(). Throws std::invalid_argument if x does not have dimension()
  /// entries, the Jacobian does not carry the pattern, or a primitive is degenerate at x
  /// (zero-area triangle, zero-length edge, non-finite coordinate), naming the pair.
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::VectorXd& values,
                Eigen::SparseMatrix<double, Eigen::RowMajor>* jacobian) override;

  /// Upper triangle of sum_k weights_k d2c_k/dx2 (1/m per unit weight) into a matrix that
  /// carries hessian_pattern(). Same exceptions as evaluate, and if weights does not have
  /// count() entries.
  void weighted_hessian(const Eigen::Ref<const Eigen::VectorXd>& x,
                        const Eigen::Ref<const Eigen::VectorXd>& weights,
                        Eigen::SparseMatrix<double>& hessian_upper) override;

  /// Contact distance (m) subtracted from each distance.
  double offset() const { return offset_; }
  const ContactGapOptions& options() const { return options_; }
  /// Distance (m) below which derivatives use the floor instead of d (see the file comment).
  double distance_floor() const { return distance_floor_; }
  /// Number of vertex-triangle pairs (they are constraints 0 .. this - 1).
  Eigen::Index vertex_triangle_count() const { return vertex_triangle_count_; }

  /// Type of pair k, 0 <= k < count() (throws std::invalid_argument naming k otherwise, as do
  /// all methods taking k).
  ContactPairType pair_type(Eigen::Index k) const;
  /// Control dofs (columns of x) that pair k depends on, sorted ascending: row k of
  /// jacobian_pattern().
  std::span<const int> pair_dofs(Eigen::Index k) const;

  /// Geometry of pair k at x (see ContactPairGeometry). Throws std::invalid_argument like
  /// evaluate.
  ContactPairGeometry pair_geometry(const Eigen::Ref<const Eigen::VectorXd>& x,
                                    Eigen::Index k) const;

  /// Distance of pair k at x with derivatives w.r.t. its 12 proxy coordinates (on the limit
  /// surface: w.r.t. its dofs, ContactPairDistance::on_pair_dofs); the Hessians only if
  /// with_hessian. The building block of constraints and penalties.
  ContactPairDistance pair_distance(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Index k,
                                    bool with_hessian) const;

  /// true if vertex-triangle pairs are measured on the limit surface (see the file comment).
  bool measures_limit_surface() const { return options_.limit_surface != nullptr; }
  /// The elements whose limit surface pair k is measured against, sorted (empty unless
  /// measured on the limit surface).
  std::span<const int> pair_surface_elements(Eigen::Index k) const;
  /// Adds `dof_gradient` (over pair_dofs(k), in that order) to `gradient` (size dimension()).
  void add_pair_dof_gradient(Eigen::Index k, const Eigen::Ref<const Eigen::VectorXd>& dof_gradient,
                             Eigen::VectorXd& gradient) const;
  /// Adds the upper triangle of `block` (symmetric, over pair_dofs(k) x pair_dofs(k)) to
  /// `hessian_upper`, which must carry hessian_pattern() (see add_pair_hessian).
  void add_pair_dof_hessian(Eigen::Index k, const Eigen::Ref<const Eigen::MatrixXd>& block,
                            Eigen::SparseMatrix<double>& hessian_upper) const;
  /// Adds J_k^T local_gradient to `gradient` (size dimension()), J_k = dy_k/dx the constant
  /// 12 x n map of pair k's proxy coordinates: pulls a gradient w.r.t. the pair's proxy
  /// coordinates back to the control dofs. Throws std::logic_error for a pair measured on the
  /// limit surface (its derivatives are in the dofs: add_pair_dof_gradient).
  void add_pair_gradient(Eigen::Index k, const Vector12d& local_gradient,
                         Eigen::VectorXd& gradient) const;

  /// Adds the upper triangle of J_k^T local_hessian J_k (local_hessian symmetric) to
  /// `hessian_upper`, which must carry hessian_pattern() (not checked here: the caller checks
  /// once per assembly, see check_hessian_structure). Throws std::logic_error for a pair
  /// measured on the limit surface (add_pair_dof_hessian).
  void add_pair_hessian(Eigen::Index k, const Matrix12d& local_hessian,
                        Eigen::SparseMatrix<double>& hessian_upper) const;

  /// Throws std::invalid_argument naming `who` unless `hessian_upper` is a compressed
  /// dimension() x dimension() matrix with as many stored entries per column as
  /// hessian_pattern() (the cheap test that it carries the pattern).
  void check_hessian_structure(const Eigen::SparseMatrix<double>& hessian_upper,
                               const char* who) const;

 private:
  struct Pair {
    ContactPairType type = ContactPairType::VertexTriangle;
    int first = -1;
    int second = -1;
    Eigen::Vector4i vertices = Eigen::Vector4i::Constant(-1);
    double mollifier_threshold = 0.0;  // eps_x (m^4) of the rest edges; 0 if not mollified
    // Measured on the limit surface: the triangle's element, and the proxy vertex as a
    // combination of control points.
    int element = -1;
    ControlPointCombination point;
    std::vector<int> candidates;  // the elements searched for the foot (sorted)
  };

  // The pairs' stencils and the Jacobian and Hessian patterns, from pairs_.
  void build_patterns();
  void check_pair_index(Eigen::Index k, const char* who) const;
  void check_x(const Eigen::Ref<const Eigen::VectorXd>& x, const char* who) const;
  // Proxy positions of the pair's four vertices, one per column (metres).
  Eigen::Matrix<double, 3, 4> pair_positions(const Eigen::Ref<const Eigen::VectorXd>& x,
                                             const Pair& pair) const;
  // J_k = dy_k/dx restricted to the pair's dofs: 12 x pair_dofs(k).size(), dimensionless.
  Eigen::Matrix<double, 12, Eigen::Dynamic> pair_map(Eigen::Index k) const;
  ContactPairDistance compute(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Index k,
                              bool with_gradient, bool with_hessian) const;
  ContactPairDistance compute_on_limit_surface(const Eigen::Ref<const Eigen::VectorXd>& x,
                                               Eigen::Index k, bool with_gradient,
                                               bool with_hessian) const;

  Eigen::Index dimension_ = 0;
  double offset_ = 0.0;
  ContactGapOptions options_;
  double distance_floor_ = 0.0;
  Eigen::Index vertex_triangle_count_ = 0;
  std::vector<Pair> pairs_;
  std::vector<Eigen::Index> dof_begin_;  // pair k's dofs are dofs_[dof_begin_[k] .. [k + 1])
  std::vector<int> dofs_;
  Eigen::SparseMatrix<double, Eigen::RowMajor> map_;  // proxy.map, row access
  Eigen::MatrixX3i triangles_;  // proxy.triangles (limit-surface pairs report their foot's)
  int segments_per_edge_ = 1;
  Eigen::SparseMatrix<double, Eigen::RowMajor> jacobian_pattern_;
  Eigen::SparseMatrix<double> hessian_pattern_;
};

}  // namespace growshell
