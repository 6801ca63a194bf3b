// nH-FastSim flexibilities: FastSim's full-adhesion forces matched to the creepage matrix K2 of
// the exact full-adhesion solution on the same patch (paper §2.3, Eq 19-21; METHOD.md §7).
//
// Without slip FastSim is linear in the creepages: F = (S D B) L^-1 c (Eq 19), S D B computed
// with the very increments the marching uses (tangential/fastsim_strips.hpp). Matching one
// entry of K3 = S D B L^-1 (Eq 20) to the same entry of K2 fixes one flexibility:
//   L1 = S(DB)_11 / K2_11,  L2 = S(DB)_22 / K2_22,  L3 = S(DB)_23 / K2_23   (term by term)
// and FastSim then reproduces K2_11, K2_22, K2_23 exactly for small creepages (to rounding).
#include <Eigen/LU>
#include <cmath>

#include <fmt/format.h>

#include "railcontact/error.hpp"
#include "railcontact/tangential.hpp"

namespace railcontact {
namespace {

// numerator / denominator, which must be a positive and finite flexibility (m/Pa).
double checked_ratio(double numerator, double denominator, const char* name, const char* entry) {
  const double L = numerator / denominator;
  require(std::isfinite(L) && L > 0.0, [&] {
    return fmt::format(
        "nH-FastSim flexibility: {} = {:.6g} / {:.6g} = {:.6g} m/Pa is not positive and finite "
        "(K2_{} has the wrong sign or vanishes on this patch)",
        name, numerator, denominator, L, entry);
  });
  return L;
}

double checked_diagonal(double value, const char* name) {
  require(std::isfinite(value) && value > 0.0, [&] {
    return fmt::format(
        "nH-FastSim flexibility: the full-matrix match (Eq 21) gives {} = {:.6g} m/Pa, "
        "not positive and finite",
        name, value);
  });
  return value;
}

}  // namespace

Flexibility nh_fastsim_flexibility(const FastSim& fastsim, const Eigen::Matrix3d& K2, FlexibilityMatch match) {
  // term_by_term reads K2_11, K2_22, K2_23 only (the force rows may come without the M3 row).
  const bool needed_finite = match == FlexibilityMatch::term_by_term
                                 ? std::isfinite(K2(0, 0)) && std::isfinite(K2(1, 1)) && std::isfinite(K2(1, 2))
                                 : K2.allFinite();
  require(needed_finite, "nH-FastSim flexibility: the creepage matrix K2 is not finite");
  const Eigen::Matrix3d& SDB = fastsim.adhesion_force_matrix();
  Flexibility L;
  switch (match) {
    case FlexibilityMatch::term_by_term:
    case FlexibilityMatch::spin_from_moment:
      L.L1 = checked_ratio(SDB(0, 0), K2(0, 0), "L1", "11");  // F1 per xi
      L.L2 = checked_ratio(SDB(1, 1), K2(1, 1), "L2", "22");  // F2 per eta
      L.L3 = match == FlexibilityMatch::term_by_term
                 ? checked_ratio(SDB(1, 2), K2(1, 2), "L3", "23")   // F2 per phi
                 : checked_ratio(SDB(2, 2), K2(2, 2), "L3", "33");  // M3 per phi
      break;
    case FlexibilityMatch::full_matrix: {
      // Eq 21: K2 = S D B L^-1  =>  L = K2^-1 S D B, of which the diagonal is kept.
      const Eigen::FullPivLU<Eigen::Matrix3d> lu(K2);
      require(lu.isInvertible(), "nH-FastSim flexibility: K2 is singular (full-matrix match, Eq 21)");
      const Eigen::Matrix3d full = lu.solve(SDB);
      L.L1 = checked_diagonal(full(0, 0), "L1");
      L.L2 = checked_diagonal(full(1, 1), "L2");
      L.L3 = checked_diagonal(full(2, 2), "L3");
      break;
    }
  }
  return L;
}

Flexibility nh_fastsim_flexibility(const ContactPatch& patch, const Eigen::Matrix3d& K2, FlexibilityMatch match) {
  return nh_fastsim_flexibility(FastSim(patch), K2, match);
}

AdhesionOptions nh_fastsim_adhesion_options() {
  AdhesionOptions options;
  options.part = CreepageMatrixPart::force_rows;
  // 1e-3: K2's force rows to ~5e-4 relative (measured on the S1002/UIC60 patches coarsened by 2:
  // at most 5.3e-4; 4e-5 with 1e-4), far below K2's discretisation error (~1 %) and the change from
  // coarsening the patch (1-3 %), with 20 % fewer GMRES iterations than 1e-4 and 60 % fewer than 1e-9.
  options.tolerance = 1e-3;
  // The adjoint solves on coarse S1002/UIC60 patches (130-800 elements) converge fastest with a
  // smaller shift than ellipses' tight solves want: 14.3 GMRES iterations for both rows at
  // gamma = 1.5 against 15.6 at 3 (mean over 30 patches); ellipses of 150-600 elements need at
  // most 6 % more iterations than at 3 (docs/FASTSIM.md).
  options.half_laplacian_gamma = 1.5;
  return options;
}

int automatic_flexibility_coarsening(const ContactPatch& patch) {
  constexpr double kMinimumCoarseElements = 250;
  constexpr std::size_t kCoarsenFrom = 400;
  const auto n = static_cast<double>(patch.elements().count());
  int factor = 1;
  while (factor < kMaximumCoarsening && n / ((factor + 1) * (factor + 1)) >= kMinimumCoarseElements) ++factor;
  if (factor == 1 && patch.elements().count() >= kCoarsenFrom) factor = 2;
  return factor;
}

Flexibility nh_fastsim_flexibility_coarsened(const ContactPatch& patch, int factor, const AdhesionOptions& options) {
  const ContactPatch coarse = coarsened(patch, factor);
  return nh_fastsim_flexibility(coarse, options);
}

Flexibility nh_fastsim_flexibility(const ContactPatch& patch, const AdhesionOptions& options, FlexibilityMatch match) {
  const AdhesionSolution adhesion = solve_full_adhesion(patch.elements(), patch.material(), options);
  return nh_fastsim_flexibility(FastSim(patch), adhesion.creepage_matrix, match);
}

}  // namespace railcontact
