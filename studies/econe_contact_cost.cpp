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

/// The fields of one trace's work (or of their sum), in the documented order.
Json trace_fields(int steps, int failed_steps, const ContactBranchCost& c) {
  const TraceCost& t = c.continuation;
  Json j;
  j["steps"] = steps;
  j["failed_steps"] = failed_steps;
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

std::string econe_contact_cost_json(const EconeContactCost& cost) {
  Json j;
  Json traces = Json::array();
  ContactBranchCost sum;
  int steps = 0, failed = 0;
  for (const EconeTraceWork& w : cost.traces) {
    // The name first, then the fields (held here: a range-for over a temporary's items()
    // would outlive it).
    const Json fields = trace_fields(w.steps, w.failed_steps, w.cost);
    Json t;
    t["trace"] = w.trace;
    for (const auto& [key, value] : fields.items()) t[key] = value;
    traces.push_back(std::move(t));
    sum.continuation += w.cost.continuation;
    sum.pair_search_seconds += w.cost.pair_search_seconds;
    sum.sample_seconds += w.cost.sample_seconds;
    sum.segments += w.cost.segments;
    sum.rebuilds_after_violation += w.cost.rebuilds_after_violation;
    sum.safeguarded_starts += w.cost.safeguarded_starts;
    sum.relaxed_starts += w.cost.relaxed_starts;
    steps += w.steps;
    failed += w.failed_steps;
  }
  j["traces"] = std::move(traces);
  j["all_traces"] = trace_fields(steps, failed, sum);
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
