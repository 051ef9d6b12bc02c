#include "studies/study_results.hpp"

#include <cmath>

#include <nlohmann/json.hpp>

#include "studies/atomic_file.hpp"
#include "studies/json_number.hpp"

namespace growshell {
namespace {

using Json = nlohmann::ordered_json;

Json mesh_json(const StudyMesh& mesh) {
  return {{"family", mesh.family},
          {"size_slope", json_number_or_null(mesh.size_slope)},
          {"elements", mesh.elements},
          {"unknowns", mesh.unknowns}};
}

}  // namespace

std::string cone_branch_results_json(const ConeBranchResults& r) {
  Json j;
  j["study"] = "cone_branch";
  j["thickness"] = json_number_or_null(r.thickness);
  j["mode"] = r.mode;
  j["mesh"] = mesh_json(r.mesh);
  j["phi_branch"] = json_number_or_null(r.phi_branch);
  j["phi_max"] = json_number_or_null(r.phi_max);
  j["eb_hat_max"] = json_number_or_null(r.eb_hat_max);
  j["phi_gap_h"] = json_number_or_null(r.phi_gap_h);
  j["phi_kiss"] = json_number_or_null(r.phi_kiss);
  j["phi_kiss_criterion"] = "midsurface_contact";
  j["phi_crit_stability"] = json_number_or_null(r.phi_crit_stability);
  j["max_s4_defect_before_contact"] = json_number_or_null(r.max_s4_defect_before_contact);
  j["phi_symmetry_lost"] = json_number_or_null(r.phi_symmetry_lost);
  j["phi_last"] = json_number_or_null(r.phi_last);
  j["phi_highest"] = json_number_or_null(r.phi_highest);
  // Flat keys, so that a sweep's tables can show them.
  const auto orientation = [&r](double ConeBranchResults::Orientation::*field) {
    return r.orientation ? json_number_or_null((*r.orientation).*field) : Json(nullptr);
  };
  using O = ConeBranchResults::Orientation;
  j["orientation_phi"] = orientation(&O::phi_e);
  j["orientation_turn_deg"] = orientation(&O::turn_deg);
  j["orientation_fold_angle_deg"] = orientation(&O::fold_angle_deg);
  j["orientation_energy_relative"] = orientation(&O::energy_relative);
  j["orientation_s4_defect"] = orientation(&O::s4_defect);
  j["orientation_chord_up"] = orientation(&O::chord_up);
  j["orientation_chord_down"] = orientation(&O::chord_down);
  j["orientation_energy_change_core"] = orientation(&O::energy_change_core);
  j["orientation_energy_change_outside"] = orientation(&O::energy_change_outside);
  j["completed"] = r.completed;
  j["end"] = r.end;
  j["branch_csv"] = "branch.csv";
  j["events"] = "events.json";
  j["wall_seconds"] = json_number_or_null(r.wall_seconds);
  return j.dump(2) + "\n";
}

void write_cone_branch_results(const std::string& directory, const ConeBranchResults& results) {
  write_file_atomically(directory + "/results.json", cone_branch_results_json(results));
}

std::string econe_contact_results_json(const EconeContactResults& r) {
  Json j;
  j["study"] = "econe_contact";
  j["thickness"] = r.thickness;
  j["mesh"] = mesh_json(r.mesh);
  j["contact_distance"] = r.contact_distance;
  j["exclusion_radius"] = r.exclusion_radius;
  j["penalty_stiffness"] = r.penalty_stiffness;
  j["contact_proxy"] = {{"segments_per_edge", r.proxy_segments_per_edge},
                        {"vertices", r.proxy_vertices},
                        {"surface", r.contact_surface}};
  j["phi_branch"] = json_number_or_null(r.phi_branch);
  j["phi_max"] = json_number_or_null(r.phi_max);
  j["eb_hat_max"] = json_number_or_null(r.eb_hat_max);
  j["phi_contact_start"] = json_number_or_null(r.phi_contact_start);
  j["phi_kiss"] = json_number_or_null(r.phi_first_contact);
  j["phi_kiss_criterion"] = "first_contact";
  j["phi_first_contact"] = json_number_or_null(r.phi_first_contact);
  j["phi_crit_stability"] = json_number_or_null(r.phi_crit_stability);
  j["phi_crit_energy"] = json_number_or_null(r.phi_crit_energy);
  j["phi_crit_energy_criterion"] =
      r.phi_crit_energy ? Json(r.phi_crit_energy_criterion) : Json(nullptr);
  j["phi_crit_energy_reference"] = r.phi_crit_energy_reference;
  Json crossings = Json::array();
  for (const EconeCrossing& c : r.crossings)
    crossings.push_back({{"phi_e", json_number_or_null(c.phi_e)},
                         {"error_estimate", json_number_or_null(c.error_estimate)},
                         {"skewed_stable", c.skewed_stable}});
  j["crossings"] = crossings;
  j["max_s4_defect_symmetric"] = json_number_or_null(r.max_s4_defect_symmetric);
  j["skewed"] = {{"found", r.skewed_found},
                 {"message", r.skewed_message},
                 {"search_at", json_number_or_null(r.skew_search_at)},
                 {"energy_below_symmetric", json_number_or_null(r.skewed_energy_below_symmetric)},
                 {"lowest_phi", json_number_or_null(r.skewed_lowest_phi)},
                 {"highest_phi", json_number_or_null(r.skewed_highest_phi)}};
  if (r.ipopt)
    j["ipopt"] = {
        {"converged", r.ipopt->converged},
        {"message", r.ipopt->message},
        {"relative_energy_difference", json_number_or_null(r.ipopt->relative_energy_difference)},
        {"state_difference_over_h", json_number_or_null(r.ipopt->state_difference_over_h)},
        {"min_distance_over_h", json_number_or_null(r.ipopt->min_distance_over_h)}};
  else
    j["ipopt"] = nullptr;
  Json hard = Json::array();
  for (const EconeHardContactPoint& p : r.hard_contact) {
    Json point = {{"branch", p.branch}, {"at", p.at}, {"file", p.file}};
    const Json check = Json::parse(hard_contact_check_json(p.check));  // outlives the loop
    for (const auto& [key, value] : check.items()) point[key] = value;
    hard.push_back(point);
  }
  j["hard_contact"] = hard;
  if (r.orientation_check) {
    const EconeOrientationCheck& o = *r.orientation_check;
    Json turned = Json::array();
    for (const EconeOrientationCheck::Turned& t : o.turned)
      turned.push_back({{"turn_deg", json_number_or_null(t.turn_deg)},
                        {"converged", t.converged},
                        {"message", t.message},
                        {"fold_angle_deg", json_number_or_null(t.fold_angle_deg)},
                        {"energy_relative", json_number_or_null(t.energy_relative)},
                        {"s4_defect", json_number_or_null(t.s4_defect)},
                        {"chord_up", json_number_or_null(t.chord_up)},
                        {"chord_down", json_number_or_null(t.chord_down)},
                        {"energy_change_core", json_number_or_null(t.energy_change_core)},
                        {"energy_change_outside", json_number_or_null(t.energy_change_outside)},
                        {"lowest_eigenvalue", json_number_or_null(t.lowest_eigenvalue)},
                        {"turn_free_index", t.turn_free_index},
                        {"state", t.state.empty() ? Json(nullptr) : Json(t.state)}});
    j["orientation_check"] = {{"phi_e", json_number_or_null(o.phi_e)},
                              {"fold_angle_deg", json_number_or_null(o.fold_angle_deg)},
                              {"s4_defect", json_number_or_null(o.s4_defect)},
                              {"core_radius", json_number_or_null(o.core_radius)},
                              {"turned", turned}};
  } else {
    j["orientation_check"] = nullptr;
  }
  if (r.turned) {
    const EconeTurnedBranch& t = *r.turned;
    j["turned"] = {
        {"start_phi", json_number_or_null(t.start_phi)},
        {"turn_deg", json_number_or_null(t.turn_deg)},
        {"lowest_phi", json_number_or_null(t.lowest_phi)},
        {"highest_phi", json_number_or_null(t.highest_phi)},
        {"lowest_phi_breaking_s4", json_number_or_null(t.lowest_phi_breaking_s4)},
        {"top_energy_relative", json_number_or_null(t.top_energy_relative)},
        {"top_s4_defect", json_number_or_null(t.top_s4_defect)},
        {"top_gamma", json_number_or_null(t.top_gamma)},
        {"largest_energy_below_symmetric", json_number_or_null(t.largest_energy_below_symmetric)},
        {"largest_energy_below_symmetric_phi",
         json_number_or_null(t.largest_energy_below_symmetric_phi)},
        {"phi_crit_stability", json_number_or_null(t.phi_crit_stability)},
        {"end", t.end}};
  } else {
    j["turned"] = nullptr;
  }
  Json modes = Json::array();
  for (const EconeComparedMode& m : r.compared_modes)
    modes.push_back(
        {{"mode", m.mode},
         {"directory", m.directory},
         {"csv", m.directory + "/branch.csv"},
         {"phi_branch", json_number_or_null(m.phi_branch)},
         {"phi_max", json_number_or_null(m.phi_max)},
         {"eb_hat_max", json_number_or_null(m.eb_hat_max)},
         {"phi_first_contact", json_number_or_null(m.phi_first_contact)},
         {"highest_phi", json_number_or_null(m.highest_phi)},
         {"lowest_energy_above_two_fold", json_number_or_null(m.lowest_energy_above_two_fold)},
         {"lowest_energy_above_two_fold_phi",
          json_number_or_null(m.lowest_energy_above_two_fold_phi)},
         {"completed", m.completed},
         {"end", m.end}});
  j["compared_modes"] = modes;
  if (r.wound) {
    const EconeWindUp& w = *r.wound;
    Json shapes = Json::array();
    for (const EconeWindUp::Shape& s : w.shapes)
      shapes.push_back(
          {{"phi_e", json_number_or_null(s.phi_e)}, {"shell", s.shell}, {"contact", s.contact}});
    j["wound"] = {{"start_branch", w.start_branch},
                  {"start_phi", json_number_or_null(w.start_phi)},
                  {"target", json_number_or_null(w.target)},
                  {"reached", w.reached},
                  {"highest_phi", json_number_or_null(w.highest_phi)},
                  {"steps", w.steps},
                  {"failed_steps", w.failed_steps},
                  {"jumps", w.jumps},
                  {"shapes", shapes},
                  {"end", w.end},
                  {"seconds", json_number_or_null(w.seconds)}};
  } else {
    j["wound"] = nullptr;
  }
  Json ratios = Json::array();
  for (const EconeEnergyRatio& e : r.energy_ratio_f)
    ratios.push_back({{"branch", e.branch},
                      {"phi_e", json_number_or_null(e.phi_e)},
                      {"f", json_number_or_null(e.f)}});
  j["energy_ratio_f"] = ratios;
  j["warnings"] = r.warnings;
  j["completed"] = r.completed;
  j["end"] = r.end;
  j["cone_csv"] = "cone/branch.csv";
  j["symmetric_csv"] = "symmetric/branch.csv";
  j["skewed_csv"] = "skewed/branch.csv";
  j["turned_csv"] = r.turned ? Json("turned/branch.csv") : Json(nullptr);
  j["wound_csv"] = r.wound ? Json("wound/branch.csv") : Json(nullptr);
  Json events = {"cone/events.json", "symmetric/events.json", "skewed/events.json"};
  if (r.turned) events.push_back("turned/events.json");
  if (r.wound) events.push_back("wound/events.json");
  j["events"] = events;
  j["wall_seconds"] = json_number_or_null(r.wall_seconds);
  return j.dump(2) + "\n";
}

}  // namespace growshell
