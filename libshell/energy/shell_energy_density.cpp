#include "libshell/energy/shell_energy_density.hpp"

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <limits>

#include "libshell/energy/dual_number.hpp"

namespace growshell {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

Matrix3d cross_matrix(const Vector3d& a) {
  Matrix3d m;
  m << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
  return m;
}

/// Quantities of the current surface shared by value, gradient and Hessian.
/// Strain-like 3-vectors are ordered (11, 22, 12).
struct JetGeometry {
  Vector3d normal;        // unit normal n = m / |m|, m = a1 x a2
  double normal_length;   // |m| = sqrt(det a)
  Matrix3d projector;     // I - n n^T
  std::array<double, 3> metric;     // a_11, a_22, a_12
  std::array<double, 3> curvature;  // b_11, b_22, b_12
  std::array<const Vector3d*, 3> second;  // a_11, a_22, a_12 (curvature order)
};

JetGeometry jet_geometry(const SurfaceJet& jet) {
  JetGeometry g;
  const Vector3d m = jet.a1.cross(jet.a2);
  g.normal_length = m.norm();
  g.normal = m / g.normal_length;
  g.projector = Matrix3d::Identity() - g.normal * g.normal.transpose();
  g.metric = {jet.a1.dot(jet.a1), jet.a2.dot(jet.a2), jet.a1.dot(jet.a2)};
  g.second = {&jet.a11, &jet.a22, &jet.a12};
  for (int i = 0; i < 3; ++i) g.curvature[i] = g.second[i]->dot(g.normal);
  return g;
}

/// Coefficient matrix D of U(E) = E^T D E for a symmetric covariant tensor E stored as
/// (E11, E22, E12): U = nu (abar^-1 : E)^2 + (1 - nu) tr(abar^-1 E abar^-1 E).
template <class T>
struct ConstitutiveMatrix {
  T d[3][3];
};

template <class T>
ConstitutiveMatrix<T> constitutive_matrix(T p, T q, T r, double nu) {
  // p, q, r: contravariant abar^11, abar^12, abar^22.
  ConstitutiveMatrix<T> D;
  D.d[0][0] = p * p;
  D.d[1][1] = r * r;
  D.d[2][2] = 4.0 * nu * q * q + (1.0 - nu) * (2.0 * q * q + 2.0 * p * r);
  D.d[0][1] = D.d[1][0] = nu * p * r + (1.0 - nu) * q * q;
  D.d[0][2] = D.d[2][0] = 2.0 * p * q;
  D.d[1][2] = D.d[2][1] = 2.0 * q * r;
  return D;
}

/// Stress-like derivatives dW/de (sigma) and dW/db (mu), the stretching tangent d2W/de2 and
/// the two energies, templated so that a Dual target metric yields their derivative with
/// respect to a growth parameter. e = (a - abar)/2 is the covariant Green strain.
template <class T>
struct MaterialResponse {
  T sigma[3];
  T mu[3];
  T stretch_tangent[3][3];  // d2 W_s / de2
  T stretching;
  T bending;
  T bending_density;  // U_b * weight * sqrt(det abar)
  ConstitutiveMatrix<T> D;
  T measure;  // weight * sqrt(det abar)
};

/// W_s = cs * measure * U_s for the Saint Venant-Kirchhoff law: U_s = e^T D e.
template <class T>
void saint_venant_kirchhoff(const JetGeometry& g, const T abar[3], T cs, MaterialResponse<T>& out) {
  T e[3], De[3];
  for (int i = 0; i < 3; ++i) e[i] = 0.5 * (g.metric[i] - abar[i]);
  T Us = 0.0;
  for (int i = 0; i < 3; ++i) {
    De[i] = out.D.d[i][0] * e[0] + out.D.d[i][1] * e[1] + out.D.d[i][2] * e[2];
    Us = Us + e[i] * De[i];
  }
  const T scale = cs * out.measure;
  out.stretching = scale * Us;
  for (int i = 0; i < 3; ++i) {
    out.sigma[i] = 2.0 * scale * De[i];
    for (int j = 0; j < 3; ++j) out.stretch_tangent[i][j] = 2.0 * scale * out.D.d[i][j];
  }
}

/// W_s = cs * measure * U_s for the neo-Hookean law with M = abar^-1 a and L = ln det M:
/// U_s = (1 - nu)/2 (tr M - 2 - L) + nu/4 L^2. Derivatives are taken in the current metric
/// a = abar + 2 e, then d/de = 2 d/da.
template <class T>
void neo_hookean(const JetGeometry& g, const T abar[3], const T contravariant[3], T cs, double nu,
                 MaterialResponse<T>& out) {
  using std::log;  // log(Dual) is found by argument-dependent lookup
  const double a11 = g.metric[0], a22 = g.metric[1], a12 = g.metric[2];
  const double det_a = a11 * a22 - a12 * a12;
  const T det_abar = abar[0] * abar[1] - abar[2] * abar[2];
  const T L = log(det_a / det_abar);
  // d tr M / da and d L / da, in the (11, 22, 12) order with a_12 counted once.
  const T trace_gradient[3] = {contravariant[0], contravariant[2], 2.0 * contravariant[1]};
  const double log_gradient[3] = {a22 / det_a, a11 / det_a, -2.0 * a12 / det_a};
  const double det_hessian[3][3] = {{0.0, 1.0, 0.0}, {1.0, 0.0, 0.0}, {0.0, 0.0, -2.0}};
  const T trace_M = trace_gradient[0] * a11 + trace_gradient[1] * a22 + trace_gradient[2] * a12;
  const T scale = cs * out.measure;
  out.stretching = scale * (0.5 * (1.0 - nu) * (trace_M - 2.0 - L) + 0.25 * nu * L * L);
  const T curvature_of_log = 0.5 * nu * L - 0.5 * (1.0 - nu);
  for (int i = 0; i < 3; ++i) {
    out.sigma[i] = 2.0 * scale *
                   (0.5 * (1.0 - nu) * (trace_gradient[i] - log_gradient[i]) +
                    0.5 * nu * L * log_gradient[i]);
    for (int j = 0; j < 3; ++j) {
      const double log_hessian =
          det_hessian[i][j] / det_a - log_gradient[i] * log_gradient[j];
      out.stretch_tangent[i][j] =
          4.0 * scale * (curvature_of_log * log_hessian +
                         0.5 * nu * log_gradient[i] * log_gradient[j]);
    }
  }
}

template <class T>
MaterialResponse<T> material_response(const JetGeometry& g, const T abar[3], double weight,
                                      double cs, double cb, const Material& material) {
  using std::sqrt;  // sqrt(Dual) is found by argument-dependent lookup
  const double nu = material.poisson_ratio;
  MaterialResponse<T> out;
  const T det = abar[0] * abar[1] - abar[2] * abar[2];
  const T p = abar[1] / det, r = abar[0] / det, q = -abar[2] / det;
  out.D = constitutive_matrix(p, q, r, nu);
  out.measure = weight * sqrt(det);
  switch (material.stretching_law) {
    case StretchingLaw::kSaintVenantKirchhoff:
      saint_venant_kirchhoff<T>(g, abar, T(cs), out);
      break;
    case StretchingLaw::kNeoHookean: {
      const T contravariant[3] = {p, q, r};
      neo_hookean<T>(g, abar, contravariant, T(cs), nu, out);
      break;
    }
  }
  T Dk[3];
  T Ub = 0.0;
  for (int i = 0; i < 3; ++i) {
    Dk[i] = out.D.d[i][0] * g.curvature[0] + out.D.d[i][1] * g.curvature[1] +
            out.D.d[i][2] * g.curvature[2];
    Ub = Ub + g.curvature[i] * Dk[i];
  }
  out.bending = cb * out.measure * Ub;
  out.bending_density = out.measure * Ub;
  for (int i = 0; i < 3; ++i) out.mu[i] = 2.0 * cb * out.measure * Dk[i];
  return out;
}

/// J_e^T sigma + J_k^T mu: the jet gradient for given stress-like vectors.
JetVector pull_back_stresses(const SurfaceJet& jet, const JetGeometry& g, const double sigma[3],
                             const double mu[3]) {
  JetVector out;
  const Vector3d v = mu[0] * jet.a11 + mu[1] * jet.a22 + mu[2] * jet.a12;
  const Vector3d w = g.projector * v / g.normal_length;
  out.segment<3>(kJetA1) = sigma[0] * jet.a1 + 0.5 * sigma[2] * jet.a2 + jet.a2.cross(w);
  out.segment<3>(kJetA2) = sigma[1] * jet.a2 + 0.5 * sigma[2] * jet.a1 + w.cross(jet.a1);
  out.segment<3>(kJetA11) = mu[0] * g.normal;
  out.segment<3>(kJetA22) = mu[1] * g.normal;
  out.segment<3>(kJetA12) = mu[2] * g.normal;
  return out;
}

/// Material response at the current surface for the rest data of one point (plain doubles).
MaterialResponse<double> response_at(const JetGeometry& g, const ShellPointRest& rest,
                                     const Material& material) {
  const double abar[3] = {rest.target_metric(0, 0), rest.target_metric(1, 1),
                          rest.target_metric(0, 1)};
  return material_response<double>(g, abar, rest.weight,
                                   stretching_modulus(material, rest.thickness),
                                   bending_modulus(material, rest.thickness), material);
}

}  // namespace

ShellPointEnergy shell_point_energy(const SurfaceJet& jet, const ShellPointRest& rest,
                                    const Material& material) {
  const JetGeometry g = jet_geometry(jet);
  const auto resp = response_at(g, rest, material);
  ShellPointEnergy out;
  out.stretching = resp.stretching;
  out.bending = g.normal_length > 0.0 ? resp.bending : std::numeric_limits<double>::quiet_NaN();
  out.bending_density_integral = resp.bending_density;
  out.current_area = rest.weight * g.normal_length;
  return out;
}

double shell_point_gradient(const SurfaceJet& jet, const ShellPointRest& rest,
                            const Material& material, JetVector& gradient) {
  const JetGeometry g = jet_geometry(jet);
  const auto resp = response_at(g, rest, material);
  gradient = pull_back_stresses(jet, g, resp.sigma, resp.mu);
  return resp.stretching + resp.bending;
}

double shell_point_hessian(const SurfaceJet& jet, const ShellPointRest& rest,
                           const Material& material, JetVector& gradient, JetMatrix& hessian) {
  const JetGeometry g = jet_geometry(jet);
  const double cb = bending_modulus(material, rest.thickness);
  const auto resp = response_at(g, rest, material);
  gradient = pull_back_stresses(jet, g, resp.sigma, resp.mu);

  const double l = g.normal_length;
  const Vector3d& n = g.normal;
  const Matrix3d& P = g.projector;
  const Matrix3d dn_da1 = -(P / l) * cross_matrix(jet.a2);  // dn/da_1
  const Matrix3d dn_da2 = (P / l) * cross_matrix(jet.a1);   // dn/da_2

  // First-order Jacobians of the strain vectors with respect to the jet.
  Eigen::Matrix<double, 3, 15> Je = Eigen::Matrix<double, 3, 15>::Zero();
  Je.block<1, 3>(0, kJetA1) = jet.a1.transpose();
  Je.block<1, 3>(1, kJetA2) = jet.a2.transpose();
  Je.block<1, 3>(2, kJetA1) = 0.5 * jet.a2.transpose();
  Je.block<1, 3>(2, kJetA2) = 0.5 * jet.a1.transpose();
  Eigen::Matrix<double, 3, 15> Jk = Eigen::Matrix<double, 3, 15>::Zero();
  const int second_block[3] = {kJetA11, kJetA22, kJetA12};
  for (int i = 0; i < 3; ++i) {
    Jk.block<1, 3>(i, second_block[i]) = n.transpose();
    Jk.block<1, 3>(i, kJetA1) = (dn_da1.transpose() * *g.second[i]).transpose();
    Jk.block<1, 3>(i, kJetA2) = (dn_da2.transpose() * *g.second[i]).transpose();
  }
  Eigen::Matrix3d Dm, Ts;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      Dm(i, j) = resp.D.d[i][j];
      Ts(i, j) = resp.stretch_tangent[i][j];
    }
  hessian.noalias() = Je.transpose() * Ts * Je;
  hessian.noalias() += Jk.transpose() * (2.0 * cb * resp.measure * Dm) * Jk;

  // Second-order terms of the metric: sigma_i d2 e_i.
  const Matrix3d I = Matrix3d::Identity();
  hessian.block<3, 3>(kJetA1, kJetA1) += resp.sigma[0] * I;
  hessian.block<3, 3>(kJetA2, kJetA2) += resp.sigma[1] * I;
  hessian.block<3, 3>(kJetA1, kJetA2) += 0.5 * resp.sigma[2] * I;
  hessian.block<3, 3>(kJetA2, kJetA1) += 0.5 * resp.sigma[2] * I;

  // Second-order terms of the curvature: mu_i d2 (a_ab(i) . n).
  for (int i = 0; i < 3; ++i) {
    const Matrix3d c1 = resp.mu[i] * dn_da1, c2 = resp.mu[i] * dn_da2;
    hessian.block<3, 3>(second_block[i], kJetA1) += c1;
    hessian.block<3, 3>(kJetA1, second_block[i]) += c1.transpose();
    hessian.block<3, 3>(second_block[i], kJetA2) += c2;
    hessian.block<3, 3>(kJetA2, second_block[i]) += c2.transpose();
  }
  // Hessian of f(a1, a2) = v . n(a1 x a2) with v = sum mu_i a_ab(i) held fixed.
  const Vector3d v = resp.mu[0] * jet.a11 + resp.mu[1] * jet.a22 + resp.mu[2] * jet.a12;
  const Vector3d Pv = P * v;
  const double vn = v.dot(n);
  const Matrix3d Hm = -(Pv * n.transpose() + n * Pv.transpose() + vn * P) / (l * l);
  Eigen::Matrix<double, 3, 6> Jm;
  Jm.leftCols<3>() = -cross_matrix(jet.a2);
  Jm.rightCols<3>() = cross_matrix(jet.a1);
  hessian.block<6, 6>(kJetA1, kJetA1) += Jm.transpose() * Hm * Jm;
  const Matrix3d W = cross_matrix(Pv / l);
  hessian.block<3, 3>(kJetA1, kJetA2) -= W;
  hessian.block<3, 3>(kJetA2, kJetA1) += W;
  return resp.stretching + resp.bending;
}

JetVector shell_point_gradient_parameter_derivative(const SurfaceJet& jet,
                                                    const ShellPointRest& rest,
                                                    const Material& material,
                                                    const Eigen::Matrix2d& dabar) {
  const JetGeometry g = jet_geometry(jet);
  const Dual abar[3] = {Dual(rest.target_metric(0, 0), dabar(0, 0)),
                        Dual(rest.target_metric(1, 1), dabar(1, 1)),
                        Dual(rest.target_metric(0, 1), dabar(0, 1))};
  const auto resp = material_response<Dual>(
      g, abar, rest.weight, stretching_modulus(material, rest.thickness),
      bending_modulus(material, rest.thickness), material);
  double dsigma[3], dmu[3];
  for (int i = 0; i < 3; ++i) {
    dsigma[i] = resp.sigma[i].derivative;
    dmu[i] = resp.mu[i].derivative;
  }
  return pull_back_stresses(jet, g, dsigma, dmu);
}

}  // namespace growshell
