// The compiled part of the Python package `growshell` (python/growshell/__init__.py wraps it):
// a shell model built from a scene, its energy, gradient and Hessian at a state and an excess
// angle, and a study run into a directory. Arrays cross as numpy arrays (copied); the Hessian
// leaves as the compressed columns of its upper triangle, which the package turns into a
// scipy.sparse matrix. Library errors become Python exceptions with the library's message
// (std::invalid_argument -> ValueError, std::runtime_error -> RuntimeError).
#include <pybind11/eigen.h>
#include <pybind11/functional.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cmath>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <tuple>

#include "libshell/assembly/shell_model.hpp"
#include "libshell/io/scene.hpp"
#include "studies/scene_study.hpp"

namespace py = pybind11;

namespace growshell {
namespace {

/// A scene file with overrides applied key by key, as `growshell run --set KEY=VALUE` does.
Scene scene_with(const std::string& path, const std::map<std::string, std::string>& overrides) {
  Scene scene = read_scene(path);
  for (const auto& [key, value] : overrides) apply_override(scene, key, value);
  validate_scene(scene);
  return scene;
}

/// A ShellModel with the scene it was built from.
class PythonModel {
 public:
  explicit PythonModel(Scene scene)
      : scene_(std::move(scene)),
        model_(std::make_unique<ShellModel>(scene_mesh(scene_), scene_model_settings(scene_))) {}

  Eigen::Index dimension() const { return model_->dimension(); }
  Eigen::Index num_elements() const { return model_->num_elements(); }
  /// The thickness at the centre (m).
  double thickness() const {
    return thickness_at_radius(scene_.thickness, 0.0, scene_.geometry.radius);
  }
  std::string scene_json() const { return scene_to_json(scene_); }
  Eigen::VectorXd reference_positions() const { return model_->reference_positions(); }

  double energy(const Eigen::VectorXd& x, double phi_e) const {
    check(x, phi_e);
    return model_->evaluate(x, phi_e, nullptr, nullptr);
  }

  Eigen::VectorXd gradient(const Eigen::VectorXd& x, double phi_e) const {
    check(x, phi_e);
    Eigen::VectorXd g;
    model_->evaluate(x, phi_e, &g, nullptr);
    return g;
  }

  /// The upper triangle of the Hessian as compressed columns: (values, row indices, column
  /// starts, n).
  std::tuple<Eigen::VectorXd, Eigen::VectorXi, Eigen::VectorXi, Eigen::Index> hessian_upper(
      const Eigen::VectorXd& x, double phi_e) const {
    check(x, phi_e);
    Eigen::SparseMatrix<double> h = model_->hessian_pattern();
    model_->evaluate(x, phi_e, nullptr, &h);
    h.makeCompressed();
    const Eigen::Index nnz = h.nonZeros(), n = h.cols();
    return {Eigen::Map<const Eigen::VectorXd>(h.valuePtr(), nnz),
            Eigen::Map<const Eigen::VectorXi>(h.innerIndexPtr(), nnz),
            Eigen::Map<const Eigen::VectorXi>(h.outerIndexPtr(), n + 1), n};
  }

  std::map<std::string, double> energy_breakdown(const Eigen::VectorXd& x, double phi_e) const {
    check(x, phi_e);
    const ShellEnergyBreakdown e = model_->energy_breakdown(x, phi_e);
    return {{"stretching", e.stretching},
            {"bending", e.bending},
            {"total", e.total()},
            {"eb_hat", e.normalized_bending()},
            {"current_area", e.current_area},
            {"grown_area", e.grown_area}};
  }

  Eigen::MatrixX3d limit_positions(const Eigen::VectorXd& x) const {
    check(x, 0.0);
    return model_->limit_positions(x);
  }

 private:
  void check(const Eigen::VectorXd& x, double phi_e) const {
    if (x.size() != model_->dimension())
      throw std::invalid_argument("x has " + std::to_string(x.size()) +
                                  " entries; the model has " +
                                  std::to_string(model_->dimension()) +
                                  " unknowns (3 per control point)");
    if (!x.allFinite()) throw std::invalid_argument("x has entries that are not finite");
    if (!model_->accepts_parameter(phi_e))
      throw std::invalid_argument("phi_e = " + std::to_string(phi_e) +
                                  ": the excess angle must be finite and > -2 pi");
  }

  Scene scene_;
  std::unique_ptr<ShellModel> model_;
};

/// Runs the study the scene names into `out` (the scene's output.directory if empty), as
/// `growshell run` does without drawing the figure. Returns (completed, end). The GIL is
/// released while the study runs and taken again for each progress line.
std::tuple<bool, std::string> run_study(const std::string& path,
                                        const std::map<std::string, std::string>& overrides,
                                        const std::string& out, const std::string& existing,
                                        const std::function<void(const std::string&)>& progress) {
  Scene scene = read_scene(path);
  for (const auto& [key, value] : overrides) apply_override(scene, key, value);
  if (!out.empty()) apply_override(scene, "output.directory", out);
  validate_scene(scene);
  ExistingOutput mode = ExistingOutput::Refuse;
  if (existing == "resume")
    mode = ExistingOutput::Resume;
  else if (existing == "overwrite")
    mode = ExistingOutput::Overwrite;
  else if (existing != "refuse")
    throw std::invalid_argument("existing = '" + existing +
                                "': must be 'refuse', 'resume' or 'overwrite'");
  check_scene_study_directory(scene, mode);
  StudyProgress log;
  if (progress)
    log = [&progress](const std::string& line) {
      py::gil_scoped_acquire gil;
      progress(line);
    };
  SceneStudyOutcome outcome;
  {
    py::gil_scoped_release release;
    outcome = run_scene_study(scene, mode, log);
  }
  return {outcome.completed, outcome.end};
}

}  // namespace
}  // namespace growshell

PYBIND11_MODULE(_growshell, m) {
  using growshell::PythonModel;
  m.doc() = "growshell's compiled core; use the package `growshell`";
  py::class_<PythonModel>(m, "Model")
      .def_property_readonly("dimension", &PythonModel::dimension)
      .def_property_readonly("num_elements", &PythonModel::num_elements)
      .def_property_readonly("thickness", &PythonModel::thickness)
      .def("scene_json", &PythonModel::scene_json)
      .def("reference_positions", &PythonModel::reference_positions)
      .def("energy", &PythonModel::energy, py::arg("x"), py::arg("phi_e"))
      .def("gradient", &PythonModel::gradient, py::arg("x"), py::arg("phi_e"))
      .def("hessian_upper", &PythonModel::hessian_upper, py::arg("x"), py::arg("phi_e"))
      .def("energy_breakdown", &PythonModel::energy_breakdown, py::arg("x"), py::arg("phi_e"))
      .def("limit_positions", &PythonModel::limit_positions, py::arg("x"));
  m.def(
      "model_from_scene",
      [](const std::string& path, const std::map<std::string, std::string>& overrides) {
        return PythonModel(growshell::scene_with(path, overrides));
      },
      py::arg("path"), py::arg("overrides"));
  m.def(
      "scene_json",
      [](const std::string& path, const std::map<std::string, std::string>& overrides) {
        return growshell::scene_to_json(growshell::scene_with(path, overrides));
      },
      py::arg("path"), py::arg("overrides"));
  m.def("run_study", &growshell::run_study, py::arg("path"), py::arg("overrides"),
        py::arg("out"), py::arg("existing"), py::arg("progress"));
}
