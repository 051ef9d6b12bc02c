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
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "core/objective_at_parameter.hpp"
#include "libshell/assembly/shell_model.hpp"
#include "libshell/io/scene.hpp"
#include "libshell/mesh/ghost_layer.hpp"
#include "python/sheet_thickness_field.hpp"
#include "solvers/continuation/pseudo_arclength.hpp"
#include "solvers/newton/newton_solver.hpp"
#include "solvers/newton/rigid_motion_pinning.hpp"
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

/// A ShellModel with the scene it was built from (for a model built from arrays, the default
/// scene with the arrays' material and centre thickness: what minimize's tolerances read).
class PythonModel {
 public:
  explicit PythonModel(Scene scene)
      : scene_(std::move(scene)),
        model_(std::make_unique<ShellModel>(scene_mesh(scene_), scene_model_settings(scene_))) {}
  PythonModel(Scene scene, const TriangleMesh& mesh, ShellModelSettings settings)
      : scene_(std::move(scene)),
        model_(std::make_unique<ShellModel>(mesh, std::move(settings))),
        from_scene_(false) {}

  Eigen::Index dimension() const { return model_->dimension(); }
  Eigen::Index num_elements() const { return model_->num_elements(); }
  /// The thickness at the centre (m); for a model built from arrays, the largest.
  double thickness() const {
    return thickness_at_radius(scene_.thickness, 0.0, scene_.geometry.radius);
  }
  /// The scene as JSON; empty for a model built from arrays.
  std::string scene_json() const { return from_scene_ ? scene_to_json(scene_) : std::string(); }
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

  /// Six dofs that remove the rigid motions, on the mesh's mirror axes (states with the
  /// mirror symmetry keep it), at state x.
  std::vector<Eigen::Index> mirror_axis_pins(const Eigen::VectorXd& x) const {
    check(x, 0.0);
    const Eigen::MatrixX3d points =
        Eigen::Map<const Eigen::Matrix<double, -1, 3, Eigen::RowMajor>>(x.data(), x.size() / 3, 3);
    return mirror_axis_pinned_dofs(points, model_->sheet_vertices(), Eigen::Vector3d::Zero());
  }

  /// Tolerances relative to the scene: `tolerance` times the natural force Y h^3 / L (N).
  double force_tolerance(double tolerance) const {
    if (!(tolerance > 0.0 && std::isfinite(tolerance)))
      throw std::invalid_argument("tolerance = " + std::to_string(tolerance) +
                                  " must be finite and > 0 (relative to Y h^3 / L)");
    return tolerance * model_->natural_force_scale();
  }

  /// Newton's method from x at phi_e with `pins` held (empty: mirror_axis_pins(x)).
  py::dict minimize(const Eigen::VectorXd& x, double phi_e, std::vector<Eigen::Index> pins,
                    double tolerance, int max_iterations) const {
    check(x, phi_e);
    if (pins.empty()) pins = mirror_axis_pins(x);
    NewtonOptions options;
    options.gradient_tolerance = force_tolerance(tolerance);
    // The pattern's turn about the axis is nearly free on a mesh: also accept a Newton
    // decrement below tolerance Y h^3 R^2 (J), as the studies do.
    const double h = thickness();
    options.decrement_tolerance = tolerance * scene_.material.youngs_modulus * h * h * h;
    options.max_iterations = max_iterations;
    NewtonResult r;
    {
      py::gil_scoped_release release;
      ObjectiveAtParameter energy(*model_, phi_e);
      r = NewtonSolver(options).minimize(energy, x, pins);
    }
    py::dict out;
    out["x"] = r.x;
    out["converged"] = r.converged();
    out["energy"] = r.energy;
    out["iterations"] = r.iterations;
    out["message"] = r.message;
    out["pins"] = pins;
    return out;
  }

  /// Pseudo-arclength continuation from the equilibrium (x, phi_e) towards increasing
  /// (direction > 0) or decreasing phi_e, up to phi_max / down to phi_min.
  py::dict trace(const Eigen::VectorXd& x, double phi_e, int direction, double phi_min,
                 double phi_max, std::vector<Eigen::Index> pins, double tolerance,
                 double max_step, double min_step, int max_steps, const std::string& corrector,
                 const std::function<void(double, int)>& progress) const {
    check(x, phi_e);
    if (direction != 1 && direction != -1)
      throw std::invalid_argument("direction must be +1 or -1");
    if (pins.empty()) pins = mirror_axis_pins(x);
    ArclengthOptions o;
    o.gradient_tolerance = force_tolerance(tolerance);
    o.max_step = max_step;
    o.min_step = min_step;
    o.initial_step = std::max(min_step, max_step / 4);
    o.parameter_min = phi_min;
    o.parameter_max = phi_max;
    o.max_steps = max_steps;
    if (corrector == "chord")
      o.corrector = ArclengthOptions::Corrector::Chord;
    else if (corrector != "newton")
      throw std::invalid_argument("corrector = '" + corrector + "': must be 'newton' or 'chord'");
    std::vector<BranchSample> samples;
    BranchTrace t;
    {
      py::gil_scoped_release release;
      t = trace_branch(*model_, x, phi_e, direction, pins, o, [&](const BranchSample& s) {
        samples.push_back(s);
        if (progress) {
          py::gil_scoped_acquire gil;
          progress(s.parameter, s.negative_eigenvalues);
        }
      });
    }
    Eigen::VectorXd phi(samples.size()), arclength(samples.size());
    Eigen::VectorXi negative(samples.size());
    Eigen::MatrixXd states(static_cast<Eigen::Index>(samples.size()), model_->dimension());
    for (std::size_t i = 0; i < samples.size(); ++i) {
      const auto k = static_cast<Eigen::Index>(i);
      phi(k) = samples[i].parameter;
      arclength(k) = samples[i].arclength;
      negative(k) = samples[i].negative_eigenvalues;
      states.row(k) = samples[i].x.transpose();
    }
    py::list special;
    for (const SpecialPoint& sp : t.special_points) {
      py::dict d;
      d["kind"] = std::string(to_string(sp.kind));
      d["phi_e"] = sp.parameter;
      d["negative_before"] = sp.negative_before;
      d["negative_after"] = sp.negative_after;
      d["bracket_width"] = sp.bracket_width;
      d["x"] = sp.x;
      special.append(d);
    }
    py::dict out;
    out["phi_e"] = phi;
    out["arclength"] = arclength;
    out["negative_eigenvalues"] = negative;
    out["states"] = states;
    out["special_points"] = special;
    out["reached_bound"] = t.reached_bound;
    out["message"] = t.message;
    out["steps"] = t.steps;
    out["factorizations"] = t.cost.factorizations;
    return out;
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
  bool from_scene_ = true;
};

/// A model of the planar sheet (vertices V x 3, z = 0; faces F x 3, counter-clockwise), its
/// ghost layer added, with thickness per vertex (V values), per face (F values) or one value.
PythonModel model_from_arrays(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces,
                              const Eigen::VectorXd& thickness, const std::string& thickness_on,
                              double youngs_modulus, double poisson_ratio,
                              const std::string& stretching_law, const Eigen::Vector2d& center,
                              double smoothing_radius, int quadrature_degree) {
  if (faces.size() > 0 && (faces.minCoeff() < 0 || faces.maxCoeff() >= vertices.rows()))
    throw std::invalid_argument("faces name vertices outside 0.." +
                                std::to_string(vertices.rows() - 1));
  Scene scene = default_scene();
  ShellModelSettings settings;
  settings.material.youngs_modulus = youngs_modulus;
  settings.material.poisson_ratio = poisson_ratio;
  if (stretching_law == "neo_hookean")
    settings.material.stretching_law = StretchingLaw::kNeoHookean;
  else if (stretching_law != "saint_venant_kirchhoff")
    throw std::invalid_argument("stretching_law = '" + stretching_law +
                                "': must be 'saint_venant_kirchhoff' or 'neo_hookean'");
  validate_material(settings.material);
  if (thickness_on == "constant") {
    if (thickness.size() != 1 || !(std::isfinite(thickness(0)) && thickness(0) > 0.0))
      throw std::invalid_argument("thickness must be one finite value > 0, or one per vertex or face");
    settings.thickness = constant_thickness(thickness(0));
  } else if (thickness_on == "vertex" || thickness_on == "face") {
    settings.thickness = sheet_thickness_field(vertices, faces, thickness, thickness_on == "face");
  } else {
    throw std::invalid_argument("thickness_on = '" + thickness_on +
                                "': must be 'constant', 'vertex' or 'face'");
  }
  if (!(smoothing_radius >= 0.0 && std::isfinite(smoothing_radius)))
    throw std::invalid_argument("smoothing_radius must be finite and >= 0");
  settings.growth.center = Eigen::Vector3d(center.x(), center.y(), 0.0);
  settings.growth.smoothing_radius = smoothing_radius;
  settings.quadrature_degree = quadrature_degree;
  scene.material.youngs_modulus = youngs_modulus;
  scene.material.poisson_ratio = poisson_ratio;
  scene.thickness = ConstantThickness{thickness.maxCoeff()};
  const TriangleMesh mesh = add_ghost_layer(TriangleMesh{vertices, faces});
  return PythonModel(std::move(scene), mesh, std::move(settings));
}

/// Runs the study the scene names into `out` (the scene's output.directory if empty), as
/// `growshell run` does without drawing the figure. Returns (completed, end). The GIL is
/// released while the study runs and taken again for each progress line.
std::tuple<bool, std::string> run_study(const std::string& path,
                                        const std::map<std::string, std::string>& overrides,
                                        const std::string& out, const std::string& existing,
                                        const std::function<void(const std::string&)>& progress) {
  std::map<std::string, std::string> keys = overrides;
  if (!out.empty()) keys["output.directory"] = out;
  const Scene scene = scene_with(path, keys);
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
      .def("limit_positions", &PythonModel::limit_positions, py::arg("x"))
      .def("mirror_axis_pins", &PythonModel::mirror_axis_pins, py::arg("x"))
      .def("minimize", &PythonModel::minimize, py::arg("x"), py::arg("phi_e"), py::arg("pins"),
           py::arg("tolerance"), py::arg("max_iterations"))
      .def("trace", &PythonModel::trace, py::arg("x"), py::arg("phi_e"), py::arg("direction"),
           py::arg("phi_min"), py::arg("phi_max"), py::arg("pins"), py::arg("tolerance"),
           py::arg("max_step"), py::arg("min_step"), py::arg("max_steps"), py::arg("corrector"),
           py::arg("progress"));
  m.def(
      "model_from_scene",
      [](const std::string& path, const std::map<std::string, std::string>& overrides) {
        return PythonModel(growshell::scene_with(path, overrides));
      },
      py::arg("path"), py::arg("overrides"));
  m.def("model_from_arrays", &growshell::model_from_arrays, py::arg("vertices"), py::arg("faces"),
        py::arg("thickness"), py::arg("thickness_on"), py::arg("youngs_modulus"),
        py::arg("poisson_ratio"), py::arg("stretching_law"), py::arg("center"),
        py::arg("smoothing_radius"), py::arg("quadrature_degree"));
  m.def(
      "scene_json",
      [](const std::string& path, const std::map<std::string, std::string>& overrides) {
        return growshell::scene_to_json(growshell::scene_with(path, overrides));
      },
      py::arg("path"), py::arg("overrides"));
  m.def("run_study", &growshell::run_study, py::arg("path"), py::arg("overrides"),
        py::arg("out"), py::arg("existing"), py::arg("progress"));
}
