#include "libshell/io/shell_snapshot.hpp"

#include <stdexcept>
#include <unordered_map>

#include "libshell/subdivision/element_lattice_sampling.hpp"

namespace growshell {

SurfaceSnapshot shell_snapshot(const ShellModel& model, const Eigen::Ref<const Eigen::VectorXd>& x,
                               double excess_angle, int refinement) {
  if (refinement < 1) throw std::invalid_argument("snapshot refinement must be >= 1");
  const Eigen::Index n_el = model.num_elements();
  const Eigen::VectorXd Ub = model.element_bending_density(x, excess_angle);
  const Eigen::VectorXd Us = model.element_stretching_density(x, excess_angle);
  const int r = refinement;
  const Eigen::Index sub = static_cast<Eigen::Index>(r) * r;
  SurfaceSnapshot s;
  if (r == 1) {
    s.points = model.limit_positions(x);
    std::unordered_map<int, int> index;
    for (std::size_t k = 0; k < model.sheet_vertices().size(); ++k)
      index[model.sheet_vertices()[k]] = static_cast<int>(k);
    s.triangles.resize(n_el, 3);
    for (Eigen::Index e = 0; e < n_el; ++e) {
      const auto& f = model.topology().face(model.patches().face[e]);
      s.triangles.row(e) << index.at(f[0]), index.at(f[1]), index.at(f[2]);
    }
  } else {
    const ElementLatticeSampling& lattice = model.lattice_sampling(r);
    const Eigen::MatrixX3d positions = lattice.state_positions(x);
    const int per_element = (r + 1) * (r + 2) / 2;
    s.points.resize(n_el * per_element, 3);
    s.triangles.resize(n_el * sub, 3);
    auto local = [r](int i, int j) { return j * (r + 1) - j * (j - 1) / 2 + i; };  // i + j <= r
    for (Eigen::Index e = 0; e < n_el; ++e) {
      const Eigen::Index base = e * per_element;
      for (int j = 0; j <= r; ++j)
        for (int i = 0; i + j <= r; ++i)
          s.points.row(base + local(i, j)) = positions.row(lattice.row(e, i, j));
      Eigen::Index t = e * sub;
      for (int j = 0; j < r; ++j) {
        for (int i = 0; i + j < r; ++i) {
          s.triangles.row(t++) << base + local(i, j), base + local(i + 1, j), base + local(i, j + 1);
          if (i + j + 1 < r)
            s.triangles.row(t++) << base + local(i + 1, j), base + local(i + 1, j + 1),
                base + local(i, j + 1);
        }
      }
    }
  }
  const Eigen::Index cells_per_element = (r == 1) ? 1 : sub;
  Eigen::VectorXd cell_Ub(n_el * cells_per_element), cell_Us(cell_Ub.size()), id(cell_Ub.size());
  for (Eigen::Index e = 0; e < n_el; ++e)
    for (Eigen::Index k = 0; k < cells_per_element; ++k) {
      cell_Ub(e * cells_per_element + k) = Ub(e);
      cell_Us(e * cells_per_element + k) = Us(e);
      id(e * cells_per_element + k) = static_cast<double>(e);
    }
  s.cell_data = {{"bending_density", cell_Ub}, {"stretching_density", cell_Us}, {"element", id}};
  return s;
}

}  // namespace growshell
