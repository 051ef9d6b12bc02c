// Consumer of the installed growshell package: includes a public header by its in-repo path,
// builds a one-triangle mesh and checks it. Exits non-zero if anything is off.
#include <cstdio>

#include "libshell/mesh/triangle_mesh.hpp"

int main() {
  growshell::TriangleMesh mesh;
  mesh.vertices.resize(3, 3);
  mesh.vertices << 0.0, 0.0, 0.0,  //
      1.0, 0.0, 0.0,               //
      0.0, 1.0, 0.0;
  mesh.faces.resize(1, 3);
  mesh.faces << 0, 1, 2;

  // Twice the signed area of the triangle: exactly 1 for this right triangle (all inputs are
  // small integers, so the floating-point result is exact).
  const Eigen::RowVector3d e1 = mesh.vertices.row(1) - mesh.vertices.row(0);
  const Eigen::RowVector3d e2 = mesh.vertices.row(2) - mesh.vertices.row(0);
  const double twice_area = e1.x() * e2.y() - e1.y() * e2.x();

  const bool ok = mesh.vertices.rows() == 3 && mesh.faces.rows() == 1 &&
                  mesh.faces.maxCoeff() == 2 && twice_area == 1.0;
  std::printf("growshell consumer: %ld vertices, %ld faces, 2*area = %g -> %s\n",
              static_cast<long>(mesh.vertices.rows()), static_cast<long>(mesh.faces.rows()),
              twice_area, ok ? "ok" : "WRONG");
  return ok ? 0 : 1;
}
