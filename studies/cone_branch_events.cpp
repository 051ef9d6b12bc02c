#include "studies/cone_branch_events.hpp"

namespace growshell {

std::vector<BranchEvent> cone_branch_events(ConeSampleMeasurer& measures, double contact_distance,
                                            bool stop_at_contact) {
  ConeSampleMeasurer* m = &measures;
  return {{"contact",
           [m, contact_distance](const BranchSample& s) { return m->gap(s.x) - contact_distance; },
           stop_at_contact},
          {"midsurface_contact", [m](const BranchSample& s) { return m->signed_gap(s.x); }, false},
          {"eb_max", [m](const BranchSample& s) { return m->eb_hat_slope(s); }, false, true}};
}

}  // namespace growshell
