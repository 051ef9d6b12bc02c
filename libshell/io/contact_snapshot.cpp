#include "libshell/io/contact_snapshot.hpp"

#include <stdexcept>
#include <string>

namespace growshell {

SurfaceSnapshot contact_snapshot(const ContactProxy& proxy, const ContactGapConstraints& gaps,
                                 const Eigen::Ref<const Eigen::VectorXd>& x,
                                 const Eigen::Ref<const Eigen::VectorXd>& forces) {
  if (x.size() != gaps.dimension())
    throw std::invalid_argument("contact_snapshot: x has " + std::to_string(x.size()) +
                                " entries, the constraints " + std::to_string(gaps.dimension()));
  if (forces.size() != gaps.count())
    throw std::invalid_argument("contact_snapshot: " + std::to_string(forces.size()) +
                                " forces for " + std::to_string(gaps.count()) + " pairs");
  SurfaceSnapshot out;
  out.points = proxy_positions(proxy, x);
  out.triangles = proxy.triangles;
  const Eigen::Index n = proxy.num_vertices();
  Eigen::MatrixX3d force_vectors = Eigen::MatrixX3d::Zero(n, 3);
  for (Eigen::Index k = 0; k < gaps.count(); ++k) {
    if (!(forces[k] > 0.0)) continue;
    const ContactPairGeometry g = gaps.pair_geometry(x, k);
    // The first primitive is pushed along +normal, the second along -normal; the weights'
    // signs say which side each vertex is on.
    for (int i = 0; i < 4; ++i)
      if (g.vertices[i] >= 0)
        force_vectors.row(g.vertices[i]) += forces[k] * g.vertex_weights[i] * g.normal.transpose();
  }
  Eigen::VectorXd magnitude = force_vectors.rowwise().norm();
  Eigen::VectorXd flag = (magnitude.array() > 0.0).cast<double>();
  Eigen::VectorXd cell_flag = Eigen::VectorXd::Zero(proxy.triangles.rows());
  for (Eigen::Index t = 0; t < proxy.triangles.rows(); ++t)
    for (int c = 0; c < 3; ++c)
      if (flag[proxy.triangles(t, c)] > 0.0) cell_flag[t] = 1.0;
  out.point_data.emplace_back("contact_force", std::move(magnitude));
  out.point_data.emplace_back("in_contact", std::move(flag));
  out.cell_data.emplace_back("in_contact", std::move(cell_flag));
  return out;
}

}  // namespace growshell
