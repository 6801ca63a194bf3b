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
#include "tangential/matrix3_eigen.hpp"

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

Flexibility nh_fastsim_flexibility(const FastSim& fastsim, const Matrix3& K2, FlexibilityMatch match) {
  // term_by_term reads K2_11, K2_22, K2_23 only (the force rows may come without the M3 row).
  const bool needed_finite = match == FlexibilityMatch::term_by_term
                                 ? std::isfinite(K2(0, 0)) && std::isfinite(K2(1, 1)) && std::isfinite(K2(1, 2))
                                 : K2.all_finite();
  require(needed_finite, "nH-FastSim flexibility: the creepage matrix K2 is not finite");
  const Matrix3& SDB = fastsim.adhesion_force_matrix();
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
      const Eigen::FullPivLU<Eigen::Matrix3d> lu(detail::to_eigen(K2));
      require(lu.isInvertible(), "nH-FastSim flexibility: K2 is singular (full-matrix match, Eq 21)");
      const Eigen::Matrix3d full = lu.solve(detail::to_eigen(SDB));
      L.L1 = checked_diagonal(full(0, 0), "L1");
      L.L2 = checked_diagonal(full(1, 1), "L2");
      L.L3 = checked_diagonal(full(2, 2), "L3");
      break;
    }
  }
  return L;
}

CreepageCoupling CreepageCoupling::moved_to(double d1_m, double d2_m, const Flexibility& L) const {
  if (none()) return *this;
  CreepageCoupling c = *this;
  c.xi_per_phi_m = xi_per_phi_m + d2_m * (1.0 - L.L1 / L.L3) - xi_per_eta * d1_m;
  c.eta_per_phi_m = eta_per_phi_m + eta_per_xi * d2_m - d1_m * (1.0 - L.L2 / L.L3);
  return c;
}

CreepageCoupling creepage_coupling(const FastSim& fastsim, const Matrix3& K2, const Flexibility& L) {
  // FastSim's full-adhesion forces per creepage, K3 = S D B L^-1 (Eq 19-20), against K2's force rows.
  const Matrix3& SDB = fastsim.adhesion_force_matrix();
  require(std::isfinite(K2(0, 1)) && std::isfinite(K2(0, 2)) && std::isfinite(K2(1, 0)) && K2(0, 0) != 0.0 &&
              K2(1, 1) != 0.0,
          "nH-FastSim creepage coupling: K2's force rows are not finite");
  CreepageCoupling c;
  c.xi_per_eta = (K2(0, 1) - SDB(0, 1) / L.L2) / K2(0, 0);
  c.xi_per_phi_m = (K2(0, 2) - SDB(0, 2) / L.L3) / K2(0, 0);
  c.eta_per_xi = (K2(1, 0) - SDB(1, 0) / L.L1) / K2(1, 1);
  c.eta_per_phi_m = (K2(1, 2) - SDB(1, 2) / L.L3) / K2(1, 1);
  return c;
}

}  // namespace railcontact
