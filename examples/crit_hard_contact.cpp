// crit_hard_contact: phi_e^crit of a trace_contact run re-located under Ipopt's hard contact
// constraints. trace_contact follows both e-cone branches with the contact penalty and puts
// phi_e^crit where their total energies cross; here the saved samples of both branches next to
// that crossing are re-solved with Ipopt (gap >= contact distance on vertex-triangle and
// edge-edge pairs) and the crossing of the re-solved elastic energies is located
// (solvers/contact/hard_contact_crossing.hpp). The difference of the two is the penalty's error
// in phi_e^crit.
//
// Reads RUN/scene.json, RUN/branch_symmetric.csv, RUN/branch_skewed.csv and the saved samples
// RUN/states_symmetric/, RUN/states_skewed/ of a trace_contact run. Writes
// OUT/hard_contact_symmetric.csv and OUT/hard_contact_skewed.csv (one row per re-solved sample,
// by its row in the branch file) and OUT/hard_contact_crossing.json.
#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "examples/support/branch_table.hpp"
#include "examples/support/directory_command_line.hpp"
#include "examples/support/guarded_main.hpp"
#include "examples/support/json_number.hpp"
#include "examples/support/saved_point.hpp"
#include "libshell/contact/contact_penalty.hpp"
#include "libshell/contact/contact_proxy.hpp"
#include "libshell/io/scene.hpp"
#include "solvers/contact/hard_contact_crossing.hpp"
#include "solvers/contact/hard_contact_solve_options.hpp"
#include "solvers/continuation/branch_crossing.hpp"
#include "solvers/newton/rigid_motion_pinning.hpp"

namespace {

using namespace growshell;
using Clock = std::chrono::steady_clock;

const char* kUsage = R"(usage: crit_hard_contact RUN [options]
  RUN                a trace_contact output directory (scene.json, branch_symmetric.csv,
                     branch_skewed.csv, states_symmetric/, states_skewed/)
  --near P           re-locate the penalty crossing nearest P (default: the lowest crossing
                     at which both branches are stable, i.e. phi_e^crit)
  --neighbours K     samples re-solved on each side beyond the two that bracket the crossing,
                     per branch (default 1: they give the interpolation error estimate)
  --segments N       the run's contact proxy: segments per element edge (default 1, as
                     trace_contact; give the run's --segments)
  --stiffness-factor F  the run's penalty stiffness factor (default 10, as trace_contact):
                     its forces warm-start Ipopt's multipliers; 0 = cold start
  --max-extensions M if the re-solved energies do not cross within those samples, re-solve up
                     to M more per branch towards the extrapolated crossing (default 6)
  --max-mismatch M   a re-solved sample is taken to have left its branch (relaxed onto another
                     one) when it and its neighbour miss the trapezoidal rule of their
                     energies and slopes by more than M of the energy change (default 0.05;
                     along one branch the miss is O(dphi^2), about 1e-4 here)
  --reuse DIR        take the re-solves already in DIR/hard_contact_<branch>.csv (an earlier
                     run of this program on the same RUN and options) instead of solving again
  --tolerance T      force tolerance of the contact-free fast path, relative to Y h^3 / R
                     (default 1e-6, as trace_contact)
  --out DIR          where to write (default RUN)
)";

struct BranchSamples {
  std::string name;
  examples::BranchTable table;
  std::vector<BranchEnergySample> penalty;  // total energy (elastic + penalty) and slope
};

BranchSamples read_branch(const std::string& run, const std::string& name) {
  BranchSamples b{name, examples::BranchTable(run + "/branch_" + name + ".csv"), {}};
  for (std::size_t i = 0; i < b.table.rows(); ++i)
    b.penalty.push_back(
        {b.table.at(i, "phi_e"),
         b.table.at(i, "E_stretch") + b.table.at(i, "E_bend") + b.table.at(i, "E_penalty"),
         b.table.at(i, "dE_dphi")});
  if (b.penalty.size() < 2)
    throw std::runtime_error(run + "/branch_" + name + ".csv has fewer than two samples");
  return b;
}

bool stable_segment(const BranchSamples& b, std::size_t i) {
  return b.table.at(i, "n_negative") == 0 && b.table.at(i + 1, "n_negative") == 0;
}

/// The saved state of `row` of branch `name`: point_NNNNN.state, or .txt from an earlier version.
std::string point_file(const std::string& run, const std::string& name, std::size_t row) {
  const std::string stem = run + "/states_" + name + "/" + saved_state_name(static_cast<int>(row));
  if (std::filesystem::exists(stem)) return stem;
  const std::string text = stem.substr(0, stem.rfind('.')) + ".txt";
  return std::filesystem::exists(text) ? text : stem;
}

/// The saved sample of `row`, checked against the table.
BranchSample load_sample(const std::string& run, const BranchSamples& b, std::size_t row,
                         Eigen::Index n) {
  const std::string file = point_file(run, b.name, row);
  BranchSample s = examples::load_point(file, n);
  const double phi = b.table.at(row, "phi_e");
  if (std::abs(s.parameter - phi) > 1e-9 * std::max(1.0, std::abs(phi)))
    throw std::runtime_error(file + " is at phi_e = " + std::to_string(s.parameter) + ", row " +
                             std::to_string(row) + " of branch_" + b.name + ".csv at " +
                             std::to_string(phi));
  return s;
}

/// The re-solved samples of one branch, by row (rows follow the branch).
using Resolved = std::map<std::size_t, HardContactSample>;

/// The converged re-solves of one branch that lie on one smooth constrained branch with the
/// rows `anchor` and `anchor + 1` (those bracketing the penalty crossing): walking outwards
/// from them, each sample must continue the last accepted one (branch_continuity_mismatch <=
/// max_mismatch); the first that does not, and all beyond it, are left out and their rows added
/// to `left`.
std::vector<BranchEnergySample> on_branch_energies(const Resolved& r, std::size_t anchor,
                                                   double max_mismatch,
                                                   std::vector<std::size_t>& left) {
  std::vector<HardContactSample> ordered;
  std::vector<std::size_t> rows;
  for (const auto& [row, s] : r)
    if (s.converged) {
      ordered.push_back(s);
      rows.push_back(row);
    }
  if (ordered.empty()) return {};
  // Start from the converged sample nearest the anchor rows.
  std::size_t start = 0;
  const auto distance = [&](std::size_t i) { return std::abs(double(rows[i]) - (anchor + 0.5)); };
  for (std::size_t i = 0; i < rows.size(); ++i)
    if (distance(i) < distance(start)) start = i;
  const auto [lo, hi] = continuous_stretch(ordered, start, max_mismatch);
  std::vector<BranchEnergySample> out;
  for (std::size_t i = 0; i < ordered.size(); ++i) {
    if (i < lo || i > hi) {
      left.push_back(rows[i]);
      continue;
    }
    out.push_back({ordered[i].parameter, ordered[i].energy, ordered[i].energy_slope});
  }
  return out;
}

/// The next row beyond the resolved ones of `b` in the direction of increasing (up) or
/// decreasing phi_e, as long as it continues the sheet (same direction in phi_e, no fold, the
/// same stability); nullopt at the sheet's end.
std::optional<std::size_t> next_row(const BranchSamples& b, const Resolved& r, bool up) {
  const std::size_t first = r.begin()->first, last = r.rbegin()->first;
  const bool rows_rise = b.table.at(last, "phi_e") > b.table.at(first, "phi_e");
  const bool forward = rows_rise == up;
  if (forward ? last + 1 >= b.table.rows() : first == 0) return std::nullopt;
  const std::size_t end = forward ? last : first;
  const std::size_t next = forward ? last + 1 : first - 1;
  const double step = b.table.at(next, "phi_e") - b.table.at(end, "phi_e");
  if ((step > 0.0) != up || b.table.at(next, "n_negative") != b.table.at(end, "n_negative"))
    return std::nullopt;
  return next;
}

using examples::json_number;

/// The crossing of `crossings` nearest `parameter`, skipping touchings (infinite error
/// estimate) if `crossings_only`; nullptr if there is none.
const EnergyCrossing* nearest_crossing(const std::vector<EnergyCrossing>& crossings,
                                       double parameter, bool crossings_only) {
  const EnergyCrossing* best = nullptr;
  for (const EnergyCrossing& c : crossings)
    if ((!crossings_only || std::isfinite(c.error_estimate)) &&
        (best == nullptr ||
         std::abs(c.parameter - parameter) < std::abs(best->parameter - parameter)))
      best = &c;
  return best;
}

int run(const std::string& run_dir, examples::CommandLine& cl) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  const double near = cl.number("--near", std::numeric_limits<double>::quiet_NaN());
  const int neighbours = cl.integer("--neighbours", 1);
  const int max_extensions = cl.integer("--max-extensions", 6);
  const double tolerance = cl.number("--tolerance", 1e-6);
  const double stiffness_factor = cl.number("--stiffness-factor", 10.0);
  const int segments = cl.integer("--segments", 1);
  const double max_mismatch = cl.number("--max-mismatch", 0.05);
  const std::string reuse_dir = cl.text("--reuse", "");
  const std::string out_dir = cl.text("--out", run_dir);
  cl.reject_unknown();
  if (neighbours < 0) throw std::invalid_argument("--neighbours must be >= 0");
  if (max_extensions < 0) throw std::invalid_argument("--max-extensions must be >= 0");
  if (!(tolerance > 0.0)) throw std::invalid_argument("--tolerance must be > 0");
  if (!(stiffness_factor >= 0.0)) throw std::invalid_argument("--stiffness-factor must be >= 0");
  if (segments < 1) throw std::invalid_argument("--segments must be >= 1");
  if (!(max_mismatch > 0.0)) throw std::invalid_argument("--max-mismatch must be > 0");

  const Scene scene = read_scene(run_dir + "/scene.json");
  validate_scene(scene);
  ShellModel model(scene_mesh(scene), scene_model_settings(scene));
  const double R = scene.geometry.radius;
  const double h = thickness_at_radius(scene.thickness, 0.0, R);
  const double Y = scene.material.youngs_modulus;
  const ContactProxy proxy = make_contact_proxy(model, segments);

  // The penalty crossing to re-locate.
  const BranchSamples symmetric = read_branch(run_dir, "symmetric");
  const BranchSamples skewed = read_branch(run_dir, "skewed");
  const std::vector<EnergyCrossing> crossings = energy_crossings(symmetric.penalty, skewed.penalty);
  const EnergyCrossing* chosen = nullptr;
  if (std::isnan(near)) {
    for (const EnergyCrossing& c : crossings)
      if (std::isfinite(c.error_estimate) && stable_segment(symmetric, c.segment_a) &&
          stable_segment(skewed, c.segment_b)) {
        chosen = &c;
        break;
      }
  } else {
    chosen = nearest_crossing(crossings, near, true);
  }
  if (chosen == nullptr)
    throw std::runtime_error(std::isnan(near)
                                 ? "the penalty energies of the two branches do not cross where "
                                   "both are stable"
                                 : "the penalty energies of the two branches do not cross");
  std::printf(
      "# %s: h = %g, %lld unknowns; penalty crossing at phi_e = %.7f (+- %.1e), "
      "symmetric rows %zu-%zu, skewed rows %zu-%zu\n",
      run_dir.c_str(), h, static_cast<long long>(model.dimension()), chosen->parameter,
      chosen->error_estimate, chosen->segment_a, chosen->segment_a + 1, chosen->segment_b,
      chosen->segment_b + 1);

  NewtonOptions newton;
  newton.gradient_tolerance = tolerance * model.natural_force_scale();
  newton.decrement_tolerance = 1e-6 * Y * h * h * h;
  HardContactCrossingOptions options;
  const double contact_distance = scene.physics.contact_distance.value_or(h);
  options.solve = hard_contact_solve_options(model, h, contact_distance,
                                                       resolved_exclusion_radius(scene), h, newton);
  options.penalty_stiffness =
      stiffness_factor * contact_stiffness_scale(Y, h, proxy_mean_edge_length(proxy));
  options.zone_link_distance = 0.1 * R;
  const Eigen::VectorXd& X = model.reference_positions();
  const auto pins = mirror_axis_pinned_dofs(
      Eigen::Map<const Eigen::Matrix<double, -1, 3, Eigen::RowMajor>>(X.data(), X.size() / 3, 3),
      model.sheet_vertices(), model.settings().growth.center);

  std::filesystem::create_directories(out_dir);
  const char* header =
      "row,phi_e,converged,E_penalty_state,E_elastic_penalty_state,E_elastic,dE_dphi,"
      "max_state_difference,min_distance,gamma,constrained_pairs,active_pairs,contact_force,"
      "rounds,iterations,seconds\n";
  // Earlier re-solves to take over (read before the files are rewritten).
  std::map<std::string, std::map<std::size_t, HardContactSample>> reused;
  if (!reuse_dir.empty())
    for (const BranchSamples* b : {&symmetric, &skewed}) {
      const std::string file = reuse_dir + "/hard_contact_" + b->name + ".csv";
      if (!std::filesystem::exists(file)) continue;
      const examples::BranchTable t(file);
      for (std::size_t i = 0; i < t.rows(); ++i) {
        const auto row = static_cast<std::size_t>(t.at(i, "row"));
        if (row >= b->table.rows() || std::abs(t.at(i, "phi_e") - b->table.at(row, "phi_e")) > 1e-9)
          throw std::runtime_error(file + " row " + std::to_string(i) + " does not belong to " +
                                   run_dir);
        HardContactSample s;
        s.parameter = t.at(i, "phi_e");
        s.converged = t.at(i, "converged") != 0;
        s.message = "taken from " + file;
        s.start_energy = t.at(i, "E_elastic_penalty_state");
        s.energy = t.at(i, "E_elastic");
        s.energy_slope = t.at(i, "dE_dphi");
        s.max_state_difference = t.at(i, "max_state_difference");
        s.min_distance = t.at(i, "min_distance");
        s.gamma = t.at(i, "gamma");
        s.constrained_pairs = static_cast<int>(t.at(i, "constrained_pairs"));
        s.active_pairs = static_cast<int>(t.at(i, "active_pairs"));
        s.total_force = t.at(i, "contact_force");
        s.rounds = static_cast<int>(t.at(i, "rounds"));
        s.iterations = static_cast<int>(t.at(i, "iterations"));
        s.seconds = t.at(i, "seconds");
        reused[b->name].emplace(row, s);
      }
    }
  std::map<std::string, std::ofstream> csv;
  for (const BranchSamples* b : {&symmetric, &skewed}) {
    std::ofstream& f = csv[b->name];
    f.open(out_dir + "/hard_contact_" + b->name + ".csv");
    if (!f)
      throw std::runtime_error("cannot write " + out_dir + "/hard_contact_" + b->name + ".csv");
    f << header << std::setprecision(12);
  }
  std::printf("%-9s %9s %14s %14s %10s %10s %7s %5s %5s %7s\n", "branch", "phi_e", "E_penalty",
              "E_hard", "max_dx", "min_dist", "gamma", "n_c", "it", "s");
  const auto wall = Clock::now();
  const Eigen::Index n = model.dimension();
  const auto resolve_row = [&](const BranchSamples& from, Resolved& into, std::size_t row) {
    if (into.count(row)) return;
    const auto old = reused[from.name].find(row);
    const HardContactSample s =
        old != reused[from.name].end()
            ? old->second
            : resolve_with_hard_contact(model, proxy, load_sample(run_dir, from, row, n), pins,
                                        options);
    const double penalty_total = from.penalty[row].energy;
    std::printf("%-9s %9.5f %14.9f %14.9f %10.3e %10.4e %7.4f %5d %5d %7.1f%s\n", from.name.c_str(),
                s.parameter, penalty_total, s.energy, s.max_state_difference, s.min_distance,
                s.gamma, s.active_pairs, s.iterations, s.seconds,
                s.converged ? "" : "  NOT CONVERGED");
    csv[from.name] << row << ',' << s.parameter << ',' << (s.converged ? 1 : 0) << ','
                   << penalty_total << ',' << s.start_energy << ',' << s.energy << ','
                   << s.energy_slope << ',' << s.max_state_difference << ',' << s.min_distance
                   << ',' << s.gamma << ',' << s.constrained_pairs << ',' << s.active_pairs << ','
                   << s.total_force << ',' << s.rounds << ',' << s.iterations << ',' << s.seconds
                   << '\n'
                   << std::flush;
    into.emplace(row, s);
  };
  Resolved resolved_a, resolved_b;
  const auto around = [&](const BranchSamples& from, Resolved& into, std::size_t segment) {
    const std::size_t first =
        segment >= static_cast<std::size_t>(neighbours) ? segment - neighbours : 0;
    const std::size_t last = std::min(from.table.rows() - 1, segment + 1 + neighbours);
    for (std::size_t r = first; r <= last; ++r) resolve_row(from, into, r);
  };
  around(symmetric, resolved_a, chosen->segment_a);
  around(skewed, resolved_b, chosen->segment_b);

  // The re-solved crossing nearest the penalty one. Where the re-solved energies do not cross
  // within the samples, both branches are extended by one sample at a time towards the root of
  // the linear extrapolation of their energy difference, along their sheets.
  const EnergyCrossing* hard = nullptr;
  std::vector<EnergyCrossing> hard_crossings;
  std::vector<std::size_t> left_a, left_b;
  std::string note;
  for (int extension = 0;; ++extension) {
    left_a.clear();
    left_b.clear();
    const std::vector<BranchEnergySample> ea =
        on_branch_energies(resolved_a, chosen->segment_a, max_mismatch, left_a);
    const std::vector<BranchEnergySample> eb =
        on_branch_energies(resolved_b, chosen->segment_b, max_mismatch, left_b);
    if (ea.size() < 2 || eb.size() < 2) {
      note = "a branch has fewer than two converged re-solves";
      break;
    }
    hard_crossings = energy_crossings(ea, eb);
    hard = nearest_crossing(hard_crossings, chosen->parameter, true);
    if (hard != nullptr) break;
    if (extension == max_extensions) {
      note = "the re-solved energies do not cross within " + std::to_string(max_extensions) +
             " extensions";
      break;
    }
    // Difference at the upper end of the overlap and its slope, from each branch's two
    // highest converged samples (Hermite, extrapolating).
    const auto top_two = [](const std::vector<BranchEnergySample>& e) {
      std::vector<BranchEnergySample> sorted = e;
      std::sort(sorted.begin(), sorted.end(),
                [](const auto& p, const auto& q) { return p.parameter < q.parameter; });
      return std::pair{sorted[sorted.size() - 2], sorted.back()};
    };
    const auto [a0, a1] = top_two(ea);
    const auto [b0, b1] = top_two(eb);
    const double at = std::min(a1.parameter, b1.parameter);
    const double difference = hermite_energy(a0, a1, at) - hermite_energy(b0, b1, at);
    const double dd = 1e-6;
    const double slope = ((hermite_energy(a0, a1, at + dd) - hermite_energy(b0, b1, at + dd)) -
                          (hermite_energy(a0, a1, at - dd) - hermite_energy(b0, b1, at - dd))) /
                         (2 * dd);
    const bool up = slope != 0.0 && at - difference / slope > at;
    // A sheet with a sample that left it ends there.
    const auto beyond = [&](const BranchSamples& b, const Resolved& r,
                            const std::vector<std::size_t>& left) -> std::optional<std::size_t> {
      for (const std::size_t row : left)
        if ((b.table.at(row, "phi_e") > at) == up) return std::nullopt;
      return next_row(b, r, up);
    };
    const std::optional<std::size_t> next_a = beyond(symmetric, resolved_a, left_a);
    const std::optional<std::size_t> next_b = beyond(skewed, resolved_b, left_b);
    if (!next_a && !next_b) {
      note = std::string("the re-solved energies do not cross; the sheets end ") +
             (up ? "above" : "below") + " the samples";
      break;
    }
    std::printf("# no crossing yet: difference %.3e J at phi_e = %.5f, extending %s\n", difference,
                at, up ? "up" : "down");
    if (next_a) resolve_row(symmetric, resolved_a, *next_a);
    if (next_b) resolve_row(skewed, resolved_b, *next_b);
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - wall).count();

  // The penalty crossing located on the re-solved rows alone, to compare like with like.
  const auto penalty_of = [](const BranchSamples& s, const Resolved& r) {
    std::vector<BranchEnergySample> out;
    for (const auto& [row, sample] : r) out.push_back(s.penalty[row]);
    return out;
  };
  const std::vector<EnergyCrossing> penalty_local =
      energy_crossings(penalty_of(symmetric, resolved_a), penalty_of(skewed, resolved_b));
  const EnergyCrossing* local = nearest_crossing(penalty_local, chosen->parameter, false);

  const auto rows_json = [](const std::vector<std::size_t>& rows) {
    std::string out = "[";
    for (std::size_t i = 0; i < rows.size(); ++i) out += (i ? ", " : "") + std::to_string(rows[i]);
    return out + "]";
  };
  for (const std::size_t row : left_a)
    std::printf("# symmetric row %zu left its branch: not used\n", row);
  for (const std::size_t row : left_b)
    std::printf("# skewed row %zu left its branch: not used\n", row);
  std::ofstream json(out_dir + "/hard_contact_crossing.json");
  json << std::setprecision(12) << "{\n  \"penalty_crossing\": " << json_number(chosen->parameter)
       << ",\n  \"penalty_crossing_error_estimate\": " << json_number(chosen->error_estimate)
       << ",\n  \"penalty_crossing_from_resolved_samples\": "
       << json_number(local ? local->parameter : NAN)
       << ",\n  \"hard_contact_crossing\": " << json_number(hard ? hard->parameter : NAN)
       << ",\n  \"hard_contact_crossing_error_estimate\": "
       << json_number(hard ? hard->error_estimate : NAN)
       << ",\n  \"hard_contact_energy\": " << json_number(hard ? hard->energy : NAN)
       << ",\n  \"hard_contact_slope_difference\": "
       << json_number(hard ? hard->slope_difference : NAN)
       << ",\n  \"proxy_segments\": " << segments
       << ",\n  \"warm_start_stiffness\": " << json_number(options.penalty_stiffness)
       << ",\n  \"left_branch_symmetric_rows\": " << rows_json(left_a)
       << ",\n  \"left_branch_skewed_rows\": " << rows_json(left_b)
       << ",\n  \"samples_symmetric\": " << resolved_a.size()
       << ",\n  \"samples_skewed\": " << resolved_b.size()
       << ",\n  \"seconds\": " << json_number(seconds) << ",\n  \"message\": \"" << note
       << "\"\n}\n";

  if (!note.empty()) std::printf("# %s\n", note.c_str());
  if (hard == nullptr) {
    std::fprintf(stderr, "crit_hard_contact: no crossing of the re-solved energies\n");
    return 1;
  }
  std::printf(
      "# phi_e^crit: penalty %.7f (same samples: %.7f), hard constraints %.7f (+- %.1e); "
      "shift %+.5f; %.0f s\n",
      chosen->parameter, local ? local->parameter : NAN, hard->parameter, hard->error_estimate,
      hard->parameter - chosen->parameter, seconds);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return growshell::examples::directory_main("crit_hard_contact", kUsage, run, argc, argv);
}
