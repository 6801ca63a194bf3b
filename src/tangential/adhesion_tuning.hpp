#pragma once
// Internal tuning of the full-adhesion Krylov solve (not part of the public API): the
// preconditioner and its shift. NhFastSim's adjoint solves use gamma = 1.5 (nh_fastsim.cpp), the
// public solve_full_adhesion gamma = 3 (steady_rolling_preconditioner.hpp explains both).
#include "railcontact/tangential.hpp"

namespace railcontact {

enum class AdhesionPreconditioner {
  marching_half_laplacian,  // FastSim marching followed by c0 - Laplacian (default)
  marching,                 // FastSim marching alone
};

struct AdhesionTuning {
  AdhesionPreconditioner preconditioner = AdhesionPreconditioner::marching_half_laplacian;
  // marching_half_laplacian's shift c0 = gamma pi^2 / (patch size sqrt(dx1 dx2)); 3 is best for
  // tight solves on ellipses, 1.5 for nH-FastSim's loose adjoint solves on coarse wheel-rail patches.
  double half_laplacian_gamma = 3.0;
};

// solve_full_adhesion with the given tuning. Throws Error unless gamma is positive and finite.
AdhesionSolution solve_full_adhesion(const ContactElements& elements, const Material& material,
                                     const AdhesionOptions& options, const AdhesionTuning& tuning);

// Empties this thread's memo of K2's adjoint solutions (docs/FASTSIM.md "K2 of a patch met
// before"), so that the next force rows are solved: for benchmarks of a solve on a patch met before.
void forget_remembered_adjoints();

}  // namespace railcontact
