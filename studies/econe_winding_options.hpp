#pragma once
/// \file
/// The settings with which the econe_contact study winds the sheet up (stage 8, study.wind_to):
/// growth in natural steps of at most 0.05 rad, each a bounded-Newton minimisation of shell +
/// penalty over every triangle near a proxy vertex, started from the secant prediction. One
/// place for the study and for bench_winding_step, which times these steps.

#include "libshell/assembly/shell_model.hpp"
#include "libshell/contact/contact_proxy.hpp"
#include "libshell/io/scene.hpp"
#include "solvers/contact/contact_growth_path.hpp"

namespace growshell {

/// The winding's options for `scene` on `model` and its contact proxy: the scene's penalty
/// (scene_contact_penalty) on every triangle near a proxy vertex, in the full space; Newton to
/// study.tolerance of the model's natural force scale, with the decrement test at
/// 1e-6 Y h^3, steps of at most h/4 per dof, the adaptive shift and 5000 steps in all; growth
/// steps of at most min(0.05, continuation.max_step). h is the thickness at the centre.
ContactGrowthOptions econe_winding_options(const Scene& scene, const ShellModel& model,
                                           const ContactProxy& proxy);

}  // namespace growshell
