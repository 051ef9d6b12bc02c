#pragma once
// The contact tests' folded disc: a 5-ring unit disc (proxy spacing about 0.12 m) folded about
// its diameter X = 0 with a 0.08 m gap between the layers (fold radius 0.04 m), the half X > 0
// lying over the half X < 0, with its contact candidates.

#include <Eigen/Core>

#include "libshell/assembly/shell_model.hpp"
#include "libshell/contact/contact_candidates.hpp"
#include "libshell/contact/contact_proxy.hpp"
#include "libshell/mesh/disc_mesh.hpp"
#include "tests/support/sheet_states.hpp"

namespace growshell::test_support {

struct FoldedDiscScene {
  static constexpr double kRho = 0.04;
  ShellModel model;
  ContactProxy proxy;
  Eigen::VectorXd x;
  ContactCandidates pairs;

  /// The fold with folded_sheet's `wobble`, the proxy with `segments_per_edge`, and the
  /// candidates within 0.12 m outside the exclusion radius 0.2 m.
  FoldedDiscScene(double wobble, int segments_per_edge)
      : model(make_disc_mesh([] {
                DiscMeshOptions o;
                o.rings = 5;
                return o;
              }()),
              ShellModelSettings{}),
        proxy(make_contact_proxy(model, segments_per_edge)),
        x(folded_sheet(model, 0.0, kRho, wobble)) {
    ContactCandidateOptions options;
    options.query_distance = 0.12;
    options.exclusion_radius = 0.2;
    pairs = find_contact_candidates(proxy, proxy_positions(proxy, x), options);
  }
};

}  // namespace growshell::test_support
