// The C++ side of tests/python/test_growshell_module.py: the energy, gradient and Hessian of a
// scene's model at a state the test builds the same way (the reference positions plus
// 1e-3 sin(0.7 i + 0.3) at entry i), printed with 17 digits as JSON so that the values through
// Python can be compared with the library's.
//   usage: python_model_values SCENE.json PHI_E
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "libshell/assembly/shell_model.hpp"
#include "libshell/io/scene.hpp"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: python_model_values SCENE.json PHI_E\n");
    return 2;
  }
  try {
    const growshell::Scene scene = growshell::read_scene(argv[1]);
    const growshell::ShellModel model(growshell::scene_mesh(scene),
                                      growshell::scene_model_settings(scene));
    const double phi = std::stod(argv[2]);
    Eigen::VectorXd x = model.reference_positions();
    for (Eigen::Index i = 0; i < x.size(); ++i)
      x(i) += 1e-3 * std::sin(0.7 * static_cast<double>(i) + 0.3);
    Eigen::VectorXd g;
    Eigen::SparseMatrix<double> h = model.hessian_pattern();
    const double e = model.evaluate(x, phi, &g, &h);
    std::printf("{\"energy\": %.17g,\n \"gradient\": [", e);
    for (Eigen::Index i = 0; i < g.size(); ++i) std::printf(i ? ", %.17g" : "%.17g", g(i));
    std::printf("],\n \"hessian_upper\": [");
    bool first = true;
    for (Eigen::Index j = 0; j < h.outerSize(); ++j)
      for (Eigen::SparseMatrix<double>::InnerIterator it(h, j); it; ++it) {
        std::printf(first ? "[%ld, %ld, %.17g]" : ", [%ld, %ld, %.17g]",
                    static_cast<long>(it.row()), static_cast<long>(j), it.value());
        first = false;
      }
    std::printf("]}\n");
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "python_model_values: %s\n", e.what());
    return 1;
  }
}
