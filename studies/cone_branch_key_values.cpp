#include "studies/cone_branch_key_values.hpp"

#include <cmath>
#include <limits>
#include <string>

namespace growshell {
namespace {

/// phi_e where the stability index and the S4 defect are first counted: the switch onto the
/// cone (the samples next to its branch point) is left out.
constexpr double kPhiCountedFrom = 0.1;

const RecordedEvent* first_event(const BranchRecord& record, const std::string& kind,
                                 const std::string& branch = "") {
  for (const RecordedEvent& e : record.events())
    if (e.kind == kind && (branch.empty() || e.branch == branch)) return &e;
  return nullptr;
}

std::optional<double> phi_of(const RecordedEvent* e) {
  return e ? std::optional<double>(e->phi_e) : std::nullopt;
}

/// The eb_max event with the largest E_b-hat, or the first if none has the value.
const RecordedEvent* largest_eb_max(const BranchRecord& record) {
  const RecordedEvent* best = first_event(record, "eb_max");
  for (const RecordedEvent& e : record.events()) {
    if (e.kind != "eb_max" || !e.value("eb_hat")) continue;
    const std::optional<double> b = best->value("eb_hat");
    if (!b || *e.value("eb_hat") > *b) best = &e;
  }
  return best;
}

}  // namespace

void set_cone_branch_key_values(const BranchRecord& record, ConeBranchResults& results) {
  // The branch point the cone left from; a record written before that event existed has the
  // first branch point instead (right for the two-fold cone, the first mode).
  const RecordedEvent* entry = first_event(record, "cone_entry");
  results.phi_branch = phi_of(entry ? entry : first_event(record, "branch_point", "flat"));
  const RecordedEvent* eb = largest_eb_max(record);
  results.phi_max = phi_of(eb);
  results.eb_hat_max = eb ? eb->value("eb_hat") : std::nullopt;
  results.phi_gap_h = phi_of(first_event(record, "contact"));
  results.phi_kiss = phi_of(first_event(record, "midsurface_contact"));
  results.phi_symmetry_lost = phi_of(first_event(record, "symmetry_lost"));

  const double contact = results.phi_gap_h.value_or(std::numeric_limits<double>::infinity());
  results.phi_crit_stability.reset();
  results.max_s4_defect_before_contact.reset();
  results.phi_last.reset();
  results.phi_highest.reset();
  for (std::size_t i = 0; i < record.rows(); ++i) {
    const double phi = record.value(i, "phi_e");
    results.phi_last = phi;
    results.phi_highest = std::max(results.phi_highest.value_or(phi), phi);
    if (!(phi >= kPhiCountedFrom)) continue;
    if (!results.phi_crit_stability && record.value(i, "n_negative") > 0)
      results.phi_crit_stability = phi;
    const double defect = record.value(i, "s4_defect");
    if (phi < contact && std::isfinite(defect) &&
        !(results.max_s4_defect_before_contact && *results.max_s4_defect_before_contact >= defect))
      results.max_s4_defect_before_contact = defect;
  }
}

}  // namespace growshell
