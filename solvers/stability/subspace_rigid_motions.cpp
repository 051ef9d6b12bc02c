#include "solvers/stability/subspace_rigid_motions.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <stdexcept>
#include <string>

#include "libshell/mesh/rigid_motion.hpp"

namespace growshell {

SubspaceRigidMotions subspace_rigid_motions(const Eigen::SparseMatrix<double>& basis,
                                            const Eigen::Ref<const Eigen::VectorXd>& x) {
  if (x.size() != basis.rows())
    throw std::invalid_argument("subspace_rigid_motions: the state has " +
                                std::to_string(x.size()) + " entries, the basis " +
                                std::to_string(basis.rows()) + " rows");
  Eigen::MatrixXd fields = rigid_velocity_fields(x);
  for (int k = 0; k < 6; ++k) {
    const double norm = fields.col(k).norm();
    if (norm > 0.0) fields.col(k) /= norm;
  }
  // Parts of the unit fields in the subspace: singular values near 1 for the rigid motions in
  // it, of the order of the state's departure from the symmetry (relative) for the others.
  SubspaceRigidMotions out;
  if (basis.cols() == 0) return out;
  const Eigen::MatrixXd reduced = basis.transpose() * fields;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(reduced, Eigen::ComputeThinU);
  const Eigen::VectorXd& sigma = svd.singularValues();
  Eigen::Index rank = 0;
  while (rank < sigma.size() && sigma(rank) > 1e-3) ++rank;
  out.motions = svd.matrixU().leftCols(rank);
  // Column-pivoted Gram-Schmidt on the modes' rows: each pin the dof with the largest
  // component left after the earlier pins' are projected out. Symmetric rigid fields have
  // many equal components (a translation along z gives every orbit of the same size the same
  // one), so the pivot is chosen among those within a relative 1e-6 of the largest by the
  // lowest index, so that a trace resumed from any of its states is parametrised as the one
  // that wrote it.
  Eigen::MatrixXd rows = out.motions.transpose();  // rank x dimension
  for (Eigen::Index k = 0; k < rank; ++k) {
    const Eigen::VectorXd norms = rows.colwise().norm().transpose();
    const double largest = norms.maxCoeff();
    Eigen::Index pivot = 0;
    while (norms(pivot) < (1.0 - 1e-6) * largest) ++pivot;
    out.pins.push_back(pivot);
    const Eigen::VectorXd q = rows.col(pivot) / norms(pivot);
    rows -= q * (q.transpose() * rows);
  }
  std::sort(out.pins.begin(), out.pins.end());
  return out;
}

}  // namespace growshell
