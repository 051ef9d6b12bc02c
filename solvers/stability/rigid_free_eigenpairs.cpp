#include "solvers/stability/rigid_free_eigenpairs.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include <Eigen/Eigenvalues>

namespace growshell {

RigidFreeEigenpairs rigid_free_eigenpairs(const Eigenpairs& pinned, const Eigen::MatrixXd& rigid,
                                          const Eigen::VectorXd& dof_mass, int count) {
  const Eigen::MatrixXd& V = pinned.vectors;
  if (count < 1) throw std::invalid_argument("rigid_free_eigenpairs: count must be >= 1");
  if (V.cols() != pinned.values.size())
    throw std::invalid_argument("rigid_free_eigenpairs: pinned has " + std::to_string(V.cols()) +
                                " vectors for " + std::to_string(pinned.values.size()) + " values");
  if (V.rows() != dof_mass.size() || rigid.rows() != dof_mass.size())
    throw std::invalid_argument("rigid_free_eigenpairs: the pinned vectors, the rigid fields and "
                                "the masses have different lengths");
  const Eigen::MatrixXd MR = dof_mass.asDiagonal() * rigid;
  // (R^T M R)^+ over the rigid fields that are there (a field outside the caller's subspace
  // projects to zero, and combinations of the others add nothing).
  Eigen::MatrixXd pseudo_inverse = Eigen::MatrixXd::Zero(rigid.cols(), rigid.cols());
  if (rigid.cols() > 0) {
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> gram(rigid.transpose() * MR);
    const double largest = gram.eigenvalues().cwiseAbs().maxCoeff();
    for (Eigen::Index j = 0; j < gram.eigenvalues().size(); ++j)
      if (gram.eigenvalues()(j) > 1e-10 * largest)
        pseudo_inverse += gram.eigenvectors().col(j) * gram.eigenvectors().col(j).transpose() /
                          gram.eigenvalues()(j);
  }
  const Eigen::MatrixXd VMR = V.transpose() * MR;
  const Eigen::MatrixXd A = pinned.values.asDiagonal();
  const Eigen::MatrixXd B =
      V.transpose() * dof_mass.asDiagonal() * V - VMR * pseudo_inverse * VMR.transpose();
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(A, B);
  if (solver.info() != Eigen::Success)
    throw std::runtime_error("rigid_free_eigenpairs: the projected mass is not positive definite "
                             "on the pinned vectors (do the pins hold the rigid motions?)");
  const Eigen::Index n = std::min<Eigen::Index>(count, solver.eigenvalues().size());
  RigidFreeEigenpairs r;
  r.values = solver.eigenvalues().head(n);
  // B-normalised Ritz coefficients give M_perp-normalised vectors, i.e. vectors whose
  // rigid-free part is M-normalised; that part is the mode.
  const Eigen::MatrixXd Y = V * solver.eigenvectors().leftCols(n);
  r.vectors = Y - rigid * (pseudo_inverse * (MR.transpose() * Y));
  return r;
}

}  // namespace growshell
