#include "solvers/newton/upper_triangle_check.hpp"

#include <stdexcept>

namespace growshell {

void check_upper_triangle(const Eigen::SparseMatrix<double>& upper, const std::string& who) {
  if (upper.rows() != upper.cols())
    throw std::invalid_argument(who + ": matrix is " + std::to_string(upper.rows()) + " x " +
                                std::to_string(upper.cols()) + ", must be square");
  if (!upper.isCompressed())
    throw std::invalid_argument(who + ": matrix must be in compressed storage (makeCompressed)");
  const int* outer = upper.outerIndexPtr();
  const int* inner = upper.innerIndexPtr();
  for (Eigen::Index col = 0; col < upper.cols(); ++col) {
    for (int k = outer[col]; k < outer[col + 1]; ++k) {
      if (inner[k] > col)
        throw std::invalid_argument(who + ": entry (" + std::to_string(inner[k]) + ", " +
                                    std::to_string(col) +
                                    ") lies below the diagonal; pass the upper triangle only");
      if (k > outer[col] && inner[k] <= inner[k - 1])
        throw std::invalid_argument(who + ": row indices of column " + std::to_string(col) +
                                    " are not strictly increasing");
    }
  }
}

}  // namespace growshell
