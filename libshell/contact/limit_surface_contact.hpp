#pragma once
/// \file
/// The limit surface as the contact surface: what ContactGapConstraints needs to measure a
/// vertex-triangle pair as the distance from the proxy vertex to the limit surface around the
/// triangle's element (limit_surface_distance.hpp), instead of to the flat proxy triangle.
///
/// Why: the distance to the piecewise-flat proxy bends around the proxy's edges with a
/// curvature of one over the distance, far above the surface's own. Where the turn of a fold
/// pattern is nearly free, that curvature, not the sheet's, decides whether a state in contact
/// is stable, and traces end where a contact vertex reaches a proxy edge (docs/contact.md, "The
/// pattern's turn in the full space"). The limit surface is C1 everywhere (C2 in regular
/// regions), so the distance to it is as smooth as the sheet.

#include <memory>
#include <vector>

#include "libshell/assembly/shell_model.hpp"
#include "libshell/subdivision/element_patches.hpp"

namespace growshell {

/// The elements' patches and each element's neighbourhood (element_neighbourhoods): a proxy
/// vertex paired with a triangle of element e is measured against the limit surface of the
/// neighbourhood of e less the elements that are the vertex's neighbours on the sheet: those
/// with a proxy vertex closer to it than `exclusion_radius` in the reference (the rule of
/// contact_candidates.hpp, applied element by element, so to about an element's width; e
/// itself always stays). Without that, the search from a triangle just beyond the exclusion
/// radius can reach the vertex's own surface. With several proxy segments per edge e itself
/// can hold proxy vertices within the radius; a foot found there would be the vertex's own
/// surface (at distance zero evaluation throws), so keep the exclusion radius several element
/// widths (the default 8 h is).
struct LimitSurfaceContact {
  ElementPatches patches;
  std::vector<std::vector<int>> neighbourhoods;
  double exclusion_radius = 0.0;  ///< m, as the contact candidates'
};

/// The limit-surface contact of `model` (its patches copied, so it outlives the model) with
/// the contact candidates' exclusion radius (m). Throws std::invalid_argument unless the
/// radius is finite and >= 0.
std::shared_ptr<const LimitSurfaceContact> make_limit_surface_contact(const ShellModel& model,
                                                                      double exclusion_radius);

}  // namespace growshell
