#include "libshell/assembly/shell_model.hpp"

#include <omp.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <numbers>
#include <stdexcept>

#include "libshell/assembly/upper_block_pattern.hpp"
#include "libshell/energy/shell_energy_density.hpp"
#include "libshell/mesh/mesh_validation.hpp"
#include "libshell/subdivision/loop_rules.hpp"

namespace growshell {
namespace {

const TriangleMesh& validated(const TriangleMesh& mesh, const ShellModelSettings& settings) {
  validate_control_mesh(mesh);
  validate_material(settings.material);
  if (settings.threads < 0) throw std::invalid_argument("threads must be >= 0 (0 = default)");
  return mesh;
}

Eigen::VectorXd flatten(const Eigen::MatrixX3d& positions) {
  Eigen::VectorXd x(3 * positions.rows());
  for (Eigen::Index v = 0; v < positions.rows(); ++v) x.segment<3>(3 * v) = positions.row(v);
  return x;
}

constexpr int dofs_of(int nodes) { return nodes == Eigen::Dynamic ? Eigen::Dynamic : 3 * nodes; }
template <int Nodes>
using ElementMatrix = Eigen::Matrix<double, dofs_of(Nodes), dofs_of(Nodes)>;

/// The patch's control points of element `patch` as rows (node i = patch.control[i]).
template <int Nodes>
Eigen::Matrix<double, Nodes, 3> element_nodes(const Eigen::Ref<const Eigen::VectorXd>& x,
                                              const LoopPatch& patch) {
  Eigen::Matrix<double, Nodes, 3> X(patch.size(), 3);
  for (int i = 0; i < patch.size(); ++i)
    X.row(i) = x.segment<3>(3 * patch.control[static_cast<std::size_t>(i)]).transpose();
  return X;
}

/// The surface jet (a_1, a_2, a_11, a_22, a_12) = X^T B.
template <int Nodes>
SurfaceJet surface_jet(const JetDerivatives<Nodes>& B, const Eigen::Matrix<double, Nodes, 3>& X) {
  const Eigen::Matrix<double, 3, 5> J = X.transpose() * B;
  return {J.col(0), J.col(1), J.col(2), J.col(3), J.col(4)};
}

/// Node forces of a jet gradient: G(i, c) = sum_k B(i, k) g_jet(3 k + c).
template <int Nodes>
void add_node_forces(const JetDerivatives<Nodes>& B, const JetVector& g_jet,
                     Eigen::Matrix<double, Nodes, 3>& G) {
  G.noalias() += B * Eigen::Map<const Eigen::Matrix<double, 3, 5>>(g_jet.data()).transpose();
}

/// H_local += J H_jet J^T for the jet map J = kron(B, I3), J(3 i + c, 3 k + c) = B(i, k), with B
/// (n x 5) the basis derivatives and H_local (3n x 3n) in node-major order 3 i + c. Entry
/// (3 a + c, 3 b + d) of J H_jet J^T is (B H_cd B^T)(a, b) with H_cd(k, l) = H_jet(3 k + c,
/// 3 l + d); since H_jet is symmetric, H_dc = H_cd^T and only the six products with c <= d are
/// formed: about a quarter of the flops of the dense products (the dominant cost of Hessian
/// assembly).
template <int Nodes>
void add_jet_congruence(const JetDerivatives<Nodes>& B, const JetMatrix& H_jet,
                        ElementMatrix<Nodes>& H_local) {
  constexpr int Dofs = dofs_of(Nodes);
  const Eigen::Index n = B.rows();
  // Strided views of the (c, d) component blocks of the jet and element matrices.
  using JetComponents =
      Eigen::Map<const Eigen::Matrix<double, 5, 5>, Eigen::Unaligned, Eigen::Stride<3 * 15, 3>>;
  using ElementComponents =
      Eigen::Map<Eigen::Matrix<double, Nodes, Nodes>, Eigen::Unaligned,
                 Eigen::Stride<Dofs == Eigen::Dynamic ? Eigen::Dynamic : 3 * Dofs, 3>>;
  const Eigen::Stride<Dofs == Eigen::Dynamic ? Eigen::Dynamic : 3 * Dofs, 3> stride(3 * 3 * n, 3);
  for (int d = 0; d < 3; ++d) {
    for (int c = 0; c <= d; ++c) {
      // lazyProduct: Eigen would send these small fixed-size products through its blocked
      // GEMM kernel, whose packing costs more than the arithmetic here.
      const Eigen::Matrix<double, Nodes, 5> BH =
          B.lazyProduct(JetComponents(H_jet.data() + c + 15 * d));
      const Eigen::Matrix<double, Nodes, Nodes> block = BH.lazyProduct(B.transpose());
      ElementComponents(H_local.data() + c + 3 * n * d, n, n, stride) += block;
      if (c != d) ElementComponents(H_local.data() + d + 3 * n * c, n, n, stride) += block.transpose();
    }
  }
}

template <int Nodes>
const JetDerivatives<Nodes>& jet_derivatives(const ReferenceQuadrature& reference, Eigen::Index e,
                                             int q);
template <>
const JetDerivatives<12>& jet_derivatives<12>(const ReferenceQuadrature& reference, Eigen::Index,
                                              int q) {
  return reference.regular_derivatives(q);
}
template <>
const JetDerivatives<Eigen::Dynamic>& jet_derivatives<Eigen::Dynamic>(
    const ReferenceQuadrature& reference, Eigen::Index e, int q) {
  return reference.irregular_derivatives(e, q);
}

/// The grown metric of one element's quadrature points at one excess angle, from the parts
/// that do not depend on it (a few flops per point, computed where the element needs them).
struct ElementGrowth {
  const TargetMetricParts* parts;  ///< the element's first quadrature point
  double excess_angle;
  Eigen::Matrix2d abar(int q) const { return target_metric(parts[q], excess_angle); }
  Eigen::Matrix2d dabar(int q) const {
    return target_metric_excess_angle_derivative(parts[q], excess_angle);
  }
};

/// What evaluate() asks of one element.
enum class Order { Energy, Gradient, Hessian };

/// Energy of element e at x and, as `order` asks, its node forces G (n x 3) and Hessian H (3n x
/// 3n, node-major), both overwritten. Nodes = 12 for a regular element, Dynamic otherwise.
template <int Nodes>
double element_terms(const ReferenceQuadrature& reference, const ElementGrowth& growth,
                     const Material& material,
                     const LoopPatch& patch, Eigen::Index e,
                     const Eigen::Ref<const Eigen::VectorXd>& x, Order order,
                     Eigen::Matrix<double, Nodes, 3>& G, ElementMatrix<Nodes>& H) {
  const int m = reference.points_per_element();
  const Eigen::Matrix<double, Nodes, 3> X = element_nodes<Nodes>(x, patch);
  if (order != Order::Energy) G.setZero(patch.size(), 3);
  if (order == Order::Hessian) H.setZero(3 * patch.size(), 3 * patch.size());
  JetVector g_jet;
  JetMatrix H_jet;
  double energy = 0.0;
  for (int q = 0; q < m; ++q) {
    const Eigen::Index i = e * m + q;
    const JetDerivatives<Nodes>& B = jet_derivatives<Nodes>(reference, e, q);
    const SurfaceJet jet = surface_jet<Nodes>(B, X);
    const ShellPointRest rest{growth.abar(q), reference.rule()[q].weight, reference.thickness(i)};
    if (order == Order::Hessian) {
      energy += shell_point_hessian(jet, rest, material, g_jet, H_jet);
      add_node_forces<Nodes>(B, g_jet, G);
      add_jet_congruence<Nodes>(B, H_jet, H);
    } else if (order == Order::Gradient) {
      energy += shell_point_gradient(jet, rest, material, g_jet);
      add_node_forces<Nodes>(B, g_jet, G);
    } else {
      energy += shell_point_energy(jet, rest, material).total();
    }
  }
  return energy;
}

/// Adds element forces G (n x 3) to the global vector g at the patch's vertices.
template <int Nodes>
void scatter_forces(const LoopPatch& patch, const Eigen::Matrix<double, Nodes, 3>& G,
                    Eigen::VectorXd& g) {
  for (int a = 0; a < patch.size(); ++a)
    g.segment<3>(3 * patch.control[static_cast<std::size_t>(a)]) += G.row(a).transpose();
}

/// Adds the upper triangle of the element Hessian H to the values of the upper pattern.
template <int Nodes>
void scatter_hessian(const LoopPatch& patch, const ElementMatrix<Nodes>& H,
                     const Eigen::SparseMatrix<double>& pattern, double* values) {
  const int n = patch.size();
  for (int a = 0; a < n; ++a) {
    for (int b = 0; b < n; ++b) {
      const int ga = patch.control[static_cast<std::size_t>(a)];
      const int gb = patch.control[static_cast<std::size_t>(b)];
      if (ga > gb) continue;
      for (int c = 0; c < 3; ++c) {  // column 3 gb + c
        const Eigen::Index k = upper_entry_index(pattern, 3 * ga, 3 * gb + c);
        const int rows = (ga == gb) ? c + 1 : 3;
        for (int r = 0; r < rows; ++r) values[k + r] += H(3 * a + r, 3 * b + c);
      }
    }
  }
}

/// Energy parts of element e (see ShellModel::element_breakdown).
template <int Nodes>
ShellEnergyBreakdown element_parts(const ReferenceQuadrature& reference,
                                   const ElementGrowth& growth, const Material& material,
                                   const LoopPatch& patch, Eigen::Index e, const Eigen::Ref<const Eigen::VectorXd>& x) {
  ShellEnergyBreakdown out;
  const int m = reference.points_per_element();
  const Eigen::Matrix<double, Nodes, 3> X = element_nodes<Nodes>(x, patch);
  for (int q = 0; q < m; ++q) {
    const Eigen::Index i = e * m + q;
    const SurfaceJet jet = surface_jet<Nodes>(jet_derivatives<Nodes>(reference, e, q), X);
    const Eigen::Matrix2d abar = growth.abar(q);
    const ShellPointRest rest{abar, reference.rule()[q].weight, reference.thickness(i)};
    const ShellPointEnergy p = shell_point_energy(jet, rest, material);
    out.stretching += p.stretching;
    out.bending += p.bending;
    out.bending_density_integral += p.bending_density_integral;
    out.stretching_density_integral += p.stretching / stretching_modulus(material, rest.thickness);
    out.current_area += p.current_area;
    out.grown_area += rest.weight * std::sqrt(abar.determinant());
  }
  return out;
}

/// d(gradient)/d(phi_e) of element e as node forces (n x 3).
template <int Nodes>
Eigen::Matrix<double, Nodes, 3> element_force_parameter_derivative(
    const ReferenceQuadrature& reference, const ElementGrowth& growth,
    const ShellModelSettings& settings, const LoopPatch& patch, Eigen::Index e,
    const Eigen::Ref<const Eigen::VectorXd>& x) {
  const int m = reference.points_per_element();
  const Eigen::Matrix<double, Nodes, 3> X = element_nodes<Nodes>(x, patch);
  Eigen::Matrix<double, Nodes, 3> G = Eigen::Matrix<double, Nodes, 3>::Zero(patch.size(), 3);
  for (int q = 0; q < m; ++q) {
    const Eigen::Index i = e * m + q;
    const JetDerivatives<Nodes>& B = jet_derivatives<Nodes>(reference, e, q);
    const SurfaceJet jet = surface_jet<Nodes>(B, X);
    const ShellPointRest rest{growth.abar(q), reference.rule()[q].weight, reference.thickness(i)};
    const Eigen::Matrix2d dabar = growth.dabar(q);
    add_node_forces<Nodes>(
        B, shell_point_gradient_parameter_derivative(jet, rest, settings.material, dabar), G);
  }
  return G;
}

std::vector<std::vector<int>> patch_controls(const ElementPatches& patches) {
  std::vector<std::vector<int>> out;
  out.reserve(patches.patch.size());
  for (const LoopPatch& p : patches.patch) out.push_back(p.control);
  return out;
}

}  // namespace

ShellModel::ShellModel(const TriangleMesh& reference_control_mesh, ShellModelSettings settings)
    : settings_(std::move(settings)),
      topology_(validated(reference_control_mesh, settings_)),
      patches_(build_element_patches(topology_)),
      reference_x_(flatten(reference_control_mesh.vertices)),
      reference_(reference_control_mesh.vertices, patches_, settings_.quadrature_degree,
                 settings_.thickness),
      lattice_sampling_(std::make_shared<LatticeSamplingCache>()) {
  std::vector<char> is_corner(topology_.num_vertices(), 0);
  for (int f : patches_.face)
    for (int v : topology_.face(f)) is_corner[v] = 1;
  for (int v = 0; v < topology_.num_vertices(); ++v)
    if (is_corner[v]) sheet_vertices_.push_back(v);
  pattern_ = upper_block_pattern(topology_.num_vertices(), patch_controls(patches_));
  growth_parts_.resize(static_cast<std::size_t>(reference_.size()));
  for (Eigen::Index i = 0; i < reference_.size(); ++i)
    growth_parts_[static_cast<std::size_t>(i)] =
        target_metric_parts(settings_.growth, reference_.position(i), reference_.tangents(i));
}

bool ShellModel::accepts_parameter(double excess_angle) const {
  return std::isfinite(excess_angle) && circumferential_stretch(excess_angle) > 0.0;
}

void ShellModel::check_excess_angle(double excess_angle) const {
  if (!accepts_parameter(excess_angle))
    throw std::invalid_argument("excess angle phi_e must be finite and > -2 pi, got " +
                                std::to_string(excess_angle));
}

int ShellModel::thread_count() const {
  return settings_.threads > 0 ? settings_.threads : omp_get_max_threads();
}

double ShellModel::evaluate(const Eigen::Ref<const Eigen::VectorXd>& x, double excess_angle,
                            Eigen::VectorXd* gradient,
                            Eigen::SparseMatrix<double>* hessian_upper) const {
  if (x.size() != dimension())
    throw std::invalid_argument("ShellModel::evaluate: x has size " + std::to_string(x.size()) +
                                ", expected " + std::to_string(dimension()));
  if (hessian_upper && hessian_upper->nonZeros() != pattern_.nonZeros())
    throw std::invalid_argument("ShellModel::evaluate: Hessian does not carry the model's pattern");
  check_excess_angle(excess_angle);
  const int m = reference_.points_per_element();
  const int threads = thread_count();
  const Eigen::Index n_el = num_elements();
  // Thread 0 scatters into the outputs, the others into buffers of their own, added in thread
  // order at the end (deterministic for a given thread count).
  if (gradient) gradient->setZero(dimension());
  if (hessian_upper)
    std::fill(hessian_upper->valuePtr(), hessian_upper->valuePtr() + pattern_.nonZeros(), 0.0);
  std::vector<Eigen::VectorXd> thread_gradient(gradient ? threads : 0);
  std::vector<Eigen::VectorXd> thread_values(hessian_upper ? threads : 0);
  for (int t = 1; t < threads; ++t) {
    if (gradient) thread_gradient[t].setZero(dimension());
    if (hessian_upper) thread_values[t].setZero(pattern_.nonZeros());
  }
  const Order order = hessian_upper ? Order::Hessian : gradient ? Order::Gradient : Order::Energy;
  std::vector<double> thread_energy(threads, 0.0);

#pragma omp parallel num_threads(threads)
  {
    const int t = omp_get_thread_num();
    Eigen::VectorXd* g_t = !gradient ? nullptr : t == 0 ? gradient : &thread_gradient[t];
    double* h_t = !hessian_upper         ? nullptr
                  : t == 0               ? hessian_upper->valuePtr()
                                         : thread_values[t].data();
    double energy = 0.0;
    Eigen::Matrix<double, 12, 3> G12;
    ElementMatrix<12> H12;
    Eigen::MatrixX3d G;
    Eigen::MatrixXd H;
#pragma omp for schedule(static)
    for (Eigen::Index e = 0; e < n_el; ++e) {
      const LoopPatch& patch = patches_.patch[static_cast<std::size_t>(e)];
      const ElementGrowth growth{&growth_parts_[static_cast<std::size_t>(e * m)], excess_angle};
      if (reference_.is_regular(e)) {
        energy += element_terms<12>(reference_, growth, settings_.material, patch, e, x, order,
                                    G12, H12);
        if (g_t) scatter_forces<12>(patch, G12, *g_t);
        if (h_t) scatter_hessian<12>(patch, H12, pattern_, h_t);
      } else {
        energy += element_terms<Eigen::Dynamic>(reference_, growth, settings_.material, patch, e,
                                                x, order, G, H);
        if (g_t) scatter_forces<Eigen::Dynamic>(patch, G, *g_t);
        if (h_t) scatter_hessian<Eigen::Dynamic>(patch, H, pattern_, h_t);
      }
    }
    thread_energy[t] = energy;
  }

  double energy = 0.0;
  for (double part : thread_energy) energy += part;
  for (int t = 1; t < threads; ++t) {
    if (gradient) *gradient += thread_gradient[t];
    if (hessian_upper)
      Eigen::Map<Eigen::VectorXd>(hessian_upper->valuePtr(), hessian_upper->nonZeros()) +=
          thread_values[t];
  }
  return energy;
}

ShellEnergyBreakdown ShellModel::element_breakdown(const Eigen::Ref<const Eigen::VectorXd>& x,
                                                  double excess_angle, Eigen::Index e) const {
  const int m = reference_.points_per_element();
  check_excess_angle(excess_angle);
  const ElementGrowth growth{&growth_parts_[static_cast<std::size_t>(e * m)], excess_angle};
  const LoopPatch& patch = patches_.patch[static_cast<std::size_t>(e)];
  return reference_.is_regular(e)
             ? element_parts<12>(reference_, growth, settings_.material, patch, e, x)
             : element_parts<Eigen::Dynamic>(reference_, growth, settings_.material, patch, e, x);
}

ShellEnergyBreakdown ShellModel::energy_breakdown(const Eigen::Ref<const Eigen::VectorXd>& x,
                                                 double excess_angle) const {
  ShellEnergyBreakdown out;
  for (Eigen::Index e = 0; e < num_elements(); ++e) {
    const ShellEnergyBreakdown b = element_breakdown(x, excess_angle, e);
    out.stretching += b.stretching;
    out.bending += b.bending;
    out.bending_density_integral += b.bending_density_integral;
    out.stretching_density_integral += b.stretching_density_integral;
    out.current_area += b.current_area;
    out.grown_area += b.grown_area;
  }
  return out;
}

Eigen::VectorXd ShellModel::gradient_parameter_derivative(const Eigen::Ref<const Eigen::VectorXd>& x,
                                                          double excess_angle) const {
  if (x.size() != dimension())
    throw std::invalid_argument("ShellModel::gradient_parameter_derivative: x has size " +
                                std::to_string(x.size()) + ", expected " +
                                std::to_string(dimension()));
  check_excess_angle(excess_angle);
  const int m = reference_.points_per_element();
  Eigen::VectorXd out = Eigen::VectorXd::Zero(dimension());
  for (Eigen::Index e = 0; e < num_elements(); ++e) {
    const LoopPatch& patch = patches_.patch[static_cast<std::size_t>(e)];
    const ElementGrowth growth{&growth_parts_[static_cast<std::size_t>(e * m)], excess_angle};
    if (reference_.is_regular(e))
      scatter_forces<12>(patch,
                         element_force_parameter_derivative<12>(reference_, growth, settings_,
                                                                patch, e, x),
                         out);
    else
      scatter_forces<Eigen::Dynamic>(
          patch,
          element_force_parameter_derivative<Eigen::Dynamic>(reference_, growth, settings_, patch,
                                                             e, x),
          out);
  }
  return out;
}

Eigen::VectorXd ShellModel::element_bending_density(const Eigen::Ref<const Eigen::VectorXd>& x,
                                                    double excess_angle) const {
  Eigen::VectorXd out(num_elements());
  for (Eigen::Index e = 0; e < num_elements(); ++e) {
    const ShellEnergyBreakdown b = element_breakdown(x, excess_angle, e);
    out(e) = b.bending_density_integral / b.grown_area;
  }
  return out;
}

Eigen::VectorXd ShellModel::element_stretching_density(const Eigen::Ref<const Eigen::VectorXd>& x,
                                                       double excess_angle) const {
  Eigen::VectorXd out(num_elements());
  for (Eigen::Index e = 0; e < num_elements(); ++e) {
    const ShellEnergyBreakdown b = element_breakdown(x, excess_angle, e);
    out(e) = b.stretching_density_integral / b.grown_area;
  }
  return out;
}

struct ShellModel::LatticeSamplingCache {
  std::mutex mutex;
  std::map<int, std::unique_ptr<const ElementLatticeSampling>> by_subdivisions;
};

const ElementLatticeSampling& ShellModel::lattice_sampling(int n) const {
  const std::lock_guard<std::mutex> lock(lattice_sampling_->mutex);
  auto& slot = lattice_sampling_->by_subdivisions[n];
  if (!slot) {
    try {
      const Eigen::MatrixX3d reference =
          Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(
              reference_x_.data(), topology_.num_vertices(), 3);
      slot = std::make_unique<const ElementLatticeSampling>(patches_, reference, n);
    } catch (...) {
      lattice_sampling_->by_subdivisions.erase(n);
      throw;
    }
  }
  return *slot;
}

Eigen::MatrixX3d ShellModel::limit_positions(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  Eigen::MatrixX3d out(sheet_vertices_.size(), 3);
  for (std::size_t k = 0; k < sheet_vertices_.size(); ++k) {
    const int v = sheet_vertices_[k];
    const auto& ring = topology_.one_ring(v);
    const double chi = loop_limit_neighbour_weight(static_cast<int>(ring.size()));
    Eigen::Vector3d p = (1.0 - chi * static_cast<double>(ring.size())) * x.segment<3>(3 * v);
    for (int u : ring) p += chi * x.segment<3>(3 * u);
    out.row(static_cast<Eigen::Index>(k)) = p;
  }
  return out;
}

double ShellModel::natural_force_scale() const {
  const double h = reference_.max_thickness();
  const double L = std::sqrt(reference_.reference_area() / std::numbers::pi);
  return settings_.material.youngs_modulus * h * h * h / L;
}

}  // namespace growshell
