#pragma once
/// \file
/// Sparsity pattern of the upper triangle of a matrix made of 3x3 vertex blocks, and the
/// lookup of where each block lives in the compressed storage.

#include <Eigen/SparseCore>
#include <algorithm>
#include <array>
#include <vector>

namespace growshell {

/// Upper-triangular (row <= column) column-major pattern with one dense 3x3 block for every
/// pair of vertices that share an element patch (the diagonal blocks keep their upper half).
/// Degree of freedom of vertex v, component c: 3 v + c. Values are zero.
/// `patches` holds each element's control vertices.
Eigen::SparseMatrix<double> upper_block_pattern(int num_vertices,
                                                const std::vector<std::vector<int>>& patches);

/// Index into matrix.valuePtr() of entry (row, col), row <= col, which must be in the pattern
/// (binary search in column `col`). Used by the assembly to scatter element blocks.
inline Eigen::Index upper_entry_index(const Eigen::SparseMatrix<double>& matrix, int row,
                                      int col) {
  const int* begin = matrix.innerIndexPtr() + matrix.outerIndexPtr()[col];
  const int* end = matrix.innerIndexPtr() + matrix.outerIndexPtr()[col + 1];
  const int* it = std::lower_bound(begin, end, row);
  return it - matrix.innerIndexPtr();
}

}  // namespace growshell
