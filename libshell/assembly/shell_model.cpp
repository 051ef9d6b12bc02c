#include "libshell/assembly/shell_model.hpp"

#include <omp.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "libshell/assembly/upper_block_pattern.hpp"
#include "libshell/energy/shell_energy_density.hpp"
#include "libshell/mesh/mesh_validation.hpp"

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

SurfaceJet make_jet(const Eigen::Matrix<double, 15, 1>& s) {
  return {s.segment<3>(kJetA1), s.segment<3>(kJetA2), s.segment<3>(kJetA11),
          s.segment<3>(kJetA22), s.segment<3>(kJetA12)};
}

/// H_local += J H_jet J^T for a jet map of the form J = kron(B, I3), J(3 i + c, 3 k + c) =
/// B(i, k), with B (12 x 5) the basis derivatives. Entry (3 a + c, 3 b + d) of J H_jet J^T is
/// (B H_cd B^T)(a, b) with H_cd(k, l) = H_jet(3 k + c, 3 l + d); since H_jet is symmetric,
/// H_dc = H_cd^T and only the six products with c <= d are formed: about a quarter of the
/// flops of the dense 36x15 products (the dominant cost of Hessian assembly).
void add_jet_congruence(const Eigen::Matrix<double, 12, 5>& B, const JetMatrix& H_jet,
                        Eigen::Matrix<double, 36, 36>& H_local) {
  // Strided views of the (c, d) component blocks of the jet and element matrices.
  using JetComponents =
      Eigen::Map<const Eigen::Matrix<double, 5, 5>, Eigen::Unaligned, Eigen::Stride<3 * 15, 3>>;
  using ElementComponents =
      Eigen::Map<Eigen::Matrix<double, 12, 12>, Eigen::Unaligned, Eigen::Stride<3 * 36, 3>>;
  for (int d = 0; d < 3; ++d) {
    for (int c = 0; c <= d; ++c) {
      // lazyProduct: Eigen would send these small fixed-size products through its blocked
      // GEMM kernel, whose packing costs more than the arithmetic here.
      const Eigen::Matrix<double, 12, 5> BH =
          B.lazyProduct(JetComponents(H_jet.data() + c + 15 * d));
      const Eigen::Matrix<double, 12, 12> block = BH.lazyProduct(B.transpose());
      ElementComponents(H_local.data() + c + 36 * d) += block;
      if (c != d) ElementComponents(H_local.data() + d + 36 * c) += block.transpose();
    }
  }
}

}  // namespace

ShellModel::ShellModel(const TriangleMesh& reference_control_mesh, ShellModelSettings settings)
    : settings_(std::move(settings)),
      topology_(validated(reference_control_mesh, settings_)),
      patches_(build_element_patches(topology_)),
      reference_x_(flatten(reference_control_mesh.vertices)),
      reference_(reference_control_mesh.vertices, patches_.control, settings_.quadrature_degree,
                 settings_.thickness) {
  std::vector<char> is_corner(topology_.num_vertices(), 0);
  for (int f : patches_.face)
    for (int v : topology_.face(f)) is_corner[v] = 1;
  for (int v = 0; v < topology_.num_vertices(); ++v)
    if (is_corner[v]) sheet_vertices_.push_back(v);
  pattern_ = upper_block_pattern(topology_.num_vertices(), patches_.control);
  set_excess_angle(0.0);
}

void ShellModel::set_excess_angle(double excess_angle) {
  if (!std::isfinite(excess_angle) || circumferential_stretch(excess_angle) <= 0.0)
    throw std::invalid_argument("excess angle phi_e must be finite and > -2 pi");
  excess_angle_ = excess_angle;
  target_metric_.resize(reference_.size());
  for (Eigen::Index i = 0; i < reference_.size(); ++i)
    target_metric_[i] = target_metric(settings_.growth, reference_.position(i),
                                      reference_.tangents(i), excess_angle_);
}

int ShellModel::thread_count() const {
  return settings_.threads > 0 ? settings_.threads : omp_get_max_threads();
}

Eigen::Matrix<double, 36, 1> ShellModel::element_coordinates(
    const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Index e) const {
  Eigen::Matrix<double, 36, 1> local;
  for (int i = 0; i < 12; ++i) local.segment<3>(3 * i) = x.segment<3>(3 * patches_.control[e][i]);
  return local;
}

double ShellModel::evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                            Eigen::VectorXd* gradient,
                            Eigen::SparseMatrix<double>* hessian_upper) {
  if (x.size() != dimension())
    throw std::invalid_argument("ShellModel::evaluate: x has size " + std::to_string(x.size()) +
                                ", expected " + std::to_string(dimension()));
  if (hessian_upper && hessian_upper->nonZeros() != pattern_.nonZeros())
    throw std::invalid_argument("ShellModel::evaluate: Hessian does not carry the model's pattern");
  const int threads = thread_count();
  const Eigen::Index n_el = num_elements();
  const int m = reference_.points_per_element();
  if (gradient) {
    thread_gradient_.resize(threads);
    for (auto& g : thread_gradient_) g.setZero(dimension());
  }
  if (hessian_upper) {
    thread_values_.resize(threads);
    for (auto& h : thread_values_) h.setZero(pattern_.nonZeros());
  }
  std::vector<double> thread_energy(threads, 0.0);
  // The jet maps are kron(B, I3); the Hessian path works with B alone (add_jet_congruence).
  std::vector<Eigen::Matrix<double, 12, 5>> basis_derivatives(m);
  for (int q = 0; q < m; ++q)
    basis_derivatives[q] << reference_.basis(q).first, reference_.basis(q).second;

#pragma omp parallel num_threads(threads)
  {
    const int t = omp_get_thread_num();
    double energy = 0.0;
    Eigen::Matrix<double, 36, 1> g_local;
    Eigen::Matrix<double, 36, 36> H_local;
    JetVector g_jet;
    JetMatrix H_jet;
#pragma omp for schedule(static)
    for (Eigen::Index e = 0; e < n_el; ++e) {
      const Eigen::Matrix<double, 36, 1> xe = element_coordinates(x, e);
      g_local.setZero();
      H_local.setZero();
      for (int q = 0; q < m; ++q) {
        const Eigen::Index i = e * m + q;
        const auto& J = reference_.jet_map(q);
        const SurfaceJet jet = make_jet(J.transpose() * xe);
        const ShellPointRest rest{target_metric_[i], reference_.rule()[q].weight,
                                  reference_.thickness(i)};
        if (hessian_upper) {
          energy += shell_point_hessian(jet, rest, settings_.material, g_jet, H_jet);
          g_local.noalias() += J * g_jet;
          add_jet_congruence(basis_derivatives[q], H_jet, H_local);
        } else if (gradient) {
          energy += shell_point_gradient(jet, rest, settings_.material, g_jet);
          g_local.noalias() += J * g_jet;
        } else {
          energy += shell_point_energy(jet, rest, settings_.material).total();
        }
      }
      const auto& patch = patches_.control[e];
      if (gradient) {
        Eigen::VectorXd& g = thread_gradient_[t];
        for (int a = 0; a < 12; ++a) g.segment<3>(3 * patch[a]) += g_local.segment<3>(3 * a);
      }
      if (hessian_upper) {
        double* values = thread_values_[t].data();
        for (int a = 0; a < 12; ++a) {
          for (int b = 0; b < 12; ++b) {
            const int ga = patch[a], gb = patch[b];
            if (ga > gb) continue;
            for (int c = 0; c < 3; ++c) {  // column 3 gb + c
              const Eigen::Index k = upper_entry_index(pattern_, 3 * ga, 3 * gb + c);
              const int rows = (ga == gb) ? c + 1 : 3;
              for (int r = 0; r < rows; ++r) values[k + r] += H_local(3 * a + r, 3 * b + c);
            }
          }
        }
      }
    }
    thread_energy[t] = energy;
  }

  double energy = 0.0;
  for (double part : thread_energy) energy += part;
  if (gradient) {
    *gradient = thread_gradient_[0];
    for (int t = 1; t < threads; ++t) *gradient += thread_gradient_[t];
  }
  if (hessian_upper) {
    Eigen::Map<Eigen::VectorXd> values(hessian_upper->valuePtr(), hessian_upper->nonZeros());
    values = thread_values_[0];
    for (int t = 1; t < threads; ++t) values += thread_values_[t];
  }
  return energy;
}

ShellEnergyBreakdown ShellModel::element_breakdown(const Eigen::Ref<const Eigen::VectorXd>& x,
                                                  Eigen::Index e) const {
  ShellEnergyBreakdown out;
  const int m = reference_.points_per_element();
  const Eigen::Matrix<double, 36, 1> xe = element_coordinates(x, e);
  for (int q = 0; q < m; ++q) {
    const Eigen::Index i = e * m + q;
    const SurfaceJet jet = make_jet(reference_.jet_map(q).transpose() * xe);
    const ShellPointRest rest{target_metric_[i], reference_.rule()[q].weight,
                              reference_.thickness(i)};
    const ShellPointEnergy p = shell_point_energy(jet, rest, settings_.material);
    out.stretching += p.stretching;
    out.bending += p.bending;
    out.bending_density_integral += p.bending_density_integral;
    out.stretching_density_integral +=
        p.stretching / stretching_modulus(settings_.material, rest.thickness);
    out.current_area += p.current_area;
    out.grown_area += rest.weight * std::sqrt(target_metric_[i].determinant());
  }
  return out;
}

ShellEnergyBreakdown ShellModel::energy_breakdown(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  ShellEnergyBreakdown out;
  for (Eigen::Index e = 0; e < num_elements(); ++e) {
    const ShellEnergyBreakdown b = element_breakdown(x, e);
    out.stretching += b.stretching;
    out.bending += b.bending;
    out.bending_density_integral += b.bending_density_integral;
    out.stretching_density_integral += b.stretching_density_integral;
    out.current_area += b.current_area;
    out.grown_area += b.grown_area;
  }
  return out;
}

Eigen::VectorXd ShellModel::gradient_excess_angle_derivative(
    const Eigen::Ref<const Eigen::VectorXd>& x) const {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(dimension());
  const int m = reference_.points_per_element();
  for (Eigen::Index e = 0; e < num_elements(); ++e) {
    const Eigen::Matrix<double, 36, 1> xe = element_coordinates(x, e);
    Eigen::Matrix<double, 36, 1> local = Eigen::Matrix<double, 36, 1>::Zero();
    for (int q = 0; q < m; ++q) {
      const Eigen::Index i = e * m + q;
      const auto& J = reference_.jet_map(q);
      const SurfaceJet jet = make_jet(J.transpose() * xe);
      const ShellPointRest rest{target_metric_[i], reference_.rule()[q].weight,
                                reference_.thickness(i)};
      const Eigen::Matrix2d dabar = target_metric_excess_angle_derivative(
          settings_.growth, reference_.position(i), reference_.tangents(i), excess_angle_);
      local.noalias() +=
          J * shell_point_gradient_parameter_derivative(jet, rest, settings_.material, dabar);
    }
    for (int a = 0; a < 12; ++a)
      out.segment<3>(3 * patches_.control[e][a]) += local.segment<3>(3 * a);
  }
  return out;
}

Eigen::VectorXd ShellModel::element_bending_density(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  Eigen::VectorXd out(num_elements());
  for (Eigen::Index e = 0; e < num_elements(); ++e) {
    const ShellEnergyBreakdown b = element_breakdown(x, e);
    out(e) = b.bending_density_integral / b.grown_area;
  }
  return out;
}

Eigen::VectorXd ShellModel::element_stretching_density(
    const Eigen::Ref<const Eigen::VectorXd>& x) const {
  Eigen::VectorXd out(num_elements());
  for (Eigen::Index e = 0; e < num_elements(); ++e) {
    const ShellEnergyBreakdown b = element_breakdown(x, e);
    out(e) = b.stretching_density_integral / b.grown_area;
  }
  return out;
}

Eigen::MatrixX3d ShellModel::limit_positions(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  Eigen::MatrixX3d out(sheet_vertices_.size(), 3);
  for (std::size_t k = 0; k < sheet_vertices_.size(); ++k) {
    const int v = sheet_vertices_[k];
    Eigen::Vector3d p = kRegularLimitCentreWeight * x.segment<3>(3 * v);
    for (int u : topology_.one_ring(v)) p += kRegularLimitNeighbourWeight * x.segment<3>(3 * u);
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
