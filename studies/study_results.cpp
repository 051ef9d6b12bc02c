#include "studies/study_results.hpp"

#include <cmath>

#include <nlohmann/json.hpp>

#include "studies/atomic_file.hpp"

namespace growshell {
namespace {

using Json = nlohmann::ordered_json;

Json number_or_null(const std::optional<double>& v) {
  return v && std::isfinite(*v) ? Json(*v) : Json(nullptr);
}

}  // namespace

std::string cone_branch_results_json(const ConeBranchResults& r) {
  Json j;
  j["study"] = "cone_branch";
  j["thickness"] = number_or_null(r.thickness);
  j["mode"] = r.mode;
  j["mesh"] = {{"family", r.mesh.family},
               {"size_slope", number_or_null(r.mesh.size_slope)},
               {"elements", r.mesh.elements},
               {"unknowns", r.mesh.unknowns}};
  j["phi_branch"] = number_or_null(r.phi_branch);
  j["phi_max"] = number_or_null(r.phi_max);
  j["eb_hat_max"] = number_or_null(r.eb_hat_max);
  j["phi_gap_h"] = number_or_null(r.phi_gap_h);
  j["phi_kiss"] = number_or_null(r.phi_kiss);
  j["phi_kiss_criterion"] = "midsurface_contact";
  j["phi_crit_stability"] = number_or_null(r.phi_crit_stability);
  j["max_s4_defect_before_contact"] = number_or_null(r.max_s4_defect_before_contact);
  j["phi_symmetry_lost"] = number_or_null(r.phi_symmetry_lost);
  j["phi_last"] = number_or_null(r.phi_last);
  j["completed"] = r.completed;
  j["end"] = r.end;
  j["branch_csv"] = "branch.csv";
  j["events"] = "events.json";
  j["wall_seconds"] = number_or_null(r.wall_seconds);
  return j.dump(2) + "\n";
}

void write_cone_branch_results(const std::string& directory, const ConeBranchResults& results) {
  write_file_atomically(directory + "/results.json", cone_branch_results_json(results));
}

}  // namespace growshell
