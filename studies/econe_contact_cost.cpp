#include "studies/econe_contact_cost.hpp"

#include <cmath>

#include <nlohmann/json.hpp>

namespace growshell {
namespace {

using Json = nlohmann::ordered_json;

Json per_step(int count, int steps) {
  if (steps <= 0) return nullptr;
  return static_cast<double>(count) / steps;
}

Json finite_or_null(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

/// The fields of one trace's work, in the documented order, after its name where `named` (the
/// sum of the traces has none).
Json trace_fields(const EconeTraceWork& w, bool named) {
  const ContactBranchCost& c = w.cost;
  const TraceCost& t = c.continuation;
  const int steps = w.steps;
  Json j;
  if (named) j["trace"] = w.trace;
  j["steps"] = steps;
  j["failed_steps"] = w.failed_steps;
  j["stalled_correctors"] = t.stalled_correctors;
  j["rejected_steps"] = t.rejected_steps;
  j["tangent_angle_rejections"] = t.tangent_angle_rejections;
  j["segments"] = c.segments;
  j["linearizations"] = t.linearizations;
  j["factorizations"] = t.factorizations;
  j["factorizations_per_step"] = per_step(t.factorizations, steps);
  j["stability_evaluations"] = t.stability_evaluations;
  j["stability_evaluations_per_step"] = per_step(t.stability_evaluations, steps);
  j["assembly_seconds"] = finite_or_null(t.assembly_seconds);
  j["factorization_seconds"] = finite_or_null(t.factorization_seconds);
  j["stability_seconds"] = finite_or_null(t.stability_seconds);
  j["pair_search_seconds"] = finite_or_null(c.pair_search_seconds);
  j["sample_seconds"] = finite_or_null(c.sample_seconds);
  j["total_seconds"] = finite_or_null(t.total_seconds);
  j["rebuilds_after_violation"] = c.rebuilds_after_violation;
  j["safeguarded_starts"] = c.safeguarded_starts;
  j["relaxed_starts"] = c.relaxed_starts;
  return j;
}

}  // namespace

EconeTraceWork all_traces(const EconeContactCost& cost) {
  EconeTraceWork sum;
  sum.trace = "all";
  for (const EconeTraceWork& w : cost.traces) {
    sum.steps += w.steps;
    sum.failed_steps += w.failed_steps;
    sum.cost += w.cost;
  }
  return sum;
}

std::string econe_contact_cost_json(const EconeContactCost& cost) {
  Json j;
  Json traces = Json::array();
  for (const EconeTraceWork& w : cost.traces) traces.push_back(trace_fields(w, true));
  j["traces"] = std::move(traces);
  j["all_traces"] = trace_fields(all_traces(cost), false);
  j["skewed_search_seconds"] =
      cost.skewed_search_seconds ? finite_or_null(*cost.skewed_search_seconds) : Json(nullptr);
  j["hard_contact_checks"] = cost.hard_contact_checks;
  j["hard_contact_seconds"] = finite_or_null(cost.hard_contact_seconds);
  if (cost.winding) {
    const EconeWindingWork& w = *cost.winding;
    j["winding"] = {{"steps", w.steps},
                    {"minimisations", w.minimisations},
                    {"newton_iterations", w.newton_iterations},
                    {"factorizations", w.factorizations},
                    {"factorizations_per_step", per_step(w.factorizations, w.steps)},
                    {"eigen_solves", w.eigen_solves},
                    {"seconds", finite_or_null(w.seconds)}};
  } else {
    j["winding"] = nullptr;
  }
  j["wall_seconds"] = finite_or_null(cost.wall_seconds);
  return j.dump(2) + "\n";
}

}  // namespace growshell
