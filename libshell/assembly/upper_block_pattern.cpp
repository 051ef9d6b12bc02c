#include "libshell/assembly/upper_block_pattern.hpp"

#include <algorithm>

namespace growshell {

Eigen::SparseMatrix<double> upper_block_pattern(int num_vertices,
                                                const std::vector<std::vector<int>>& patches) {
  // Vertex-level upper adjacency: for each column vertex, the row vertices <= it.
  std::vector<std::vector<int>> rows_of(num_vertices);
  for (const auto& patch : patches)
    for (int a : patch)
      for (int b : patch)
        if (a <= b) rows_of[b].push_back(a);
  Eigen::Index nnz = 0;
  for (auto& rows : rows_of) {
    std::sort(rows.begin(), rows.end());
    rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
    nnz += 9 * static_cast<Eigen::Index>(rows.size());
  }
  const int n = 3 * num_vertices;
  Eigen::SparseMatrix<double> pattern(n, n);
  pattern.resizeNonZeros(nnz);
  int* outer = pattern.outerIndexPtr();
  int* inner = pattern.innerIndexPtr();
  int k = 0;
  for (int v = 0; v < num_vertices; ++v) {
    for (int c = 0; c < 3; ++c) {
      outer[3 * v + c] = k;
      for (int u : rows_of[v]) {
        const int rows_in_block = (u == v) ? c + 1 : 3;
        for (int r = 0; r < rows_in_block; ++r) inner[k++] = 3 * u + r;
      }
    }
  }
  outer[n] = k;
  pattern.resizeNonZeros(k);
  std::fill(pattern.valuePtr(), pattern.valuePtr() + k, 0.0);
  return pattern;
}

}  // namespace growshell
