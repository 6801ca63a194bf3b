#pragma once
// FastSim on a regular mesh (paper §2.1, Eq 1-9; METHOD.md §7) and the nH-FastSim
// flexibilities matched to the full-adhesion creepage matrix K2 (paper §2.3, Eq 19-21).
//
// Frame and signs (METHOD.md §2): X1 rolling direction, the leading edge of a strip run at its
// largest x1; Kalker's sign convention, F1 = -f11 xi, F2 = -f22 eta - f23 phi,
// M3 = f23 eta - f33 phi in the linear regime. Forces are those on the wheel (upper body).
//
// The algorithm, per strip run (consecutive contact elements at one x2):
//  1. the normal pressure is replaced by a traction bound mu p3e with the run's own leading and
//     trailing edges and the same discrete strip force: the paper's parabola (Eq 1) or, by
//     default, that parabola skewed towards the trailing edge (TractionBound below);
//  2. the run is marched from the leading edge: the leading element gets the adhesion traction
//     of Eq 2-3 at its centre, each following element the previous element's traction plus the
//     increment of Eq 2-3 between the two centres; the sum is limited to |p| <= mu p3e by
//     scaling (Eq 7-8), and the limited traction is the start of the next increment (Kalker's
//     FASTSIM). Elements where the limit is active slip.
// For pure creepage (phi = 0) this equals element-wise clipping of Eq 2-3; with spin it does not.
#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "railcontact/adhesion.hpp"
#include "railcontact/creepage.hpp"
#include "railcontact/kalker.hpp"
#include "railcontact/patch.hpp"

namespace railcontact {

// FastSim's traction bound (docs/FASTSIM.md §1, §6). Per strip run the normal pressure is
// replaced by
//   p3e = h t (1 - t) (1 + skew t),   t = (x_l - x1) / (x_l - x_t)  (0 at the leading edge),
// h keeping the run's strip force. skew = 0 is the paper's per-strip parabola (Eq 1);
// skew = 1 is the bound with which FastSim reproduces Carter's exact two-dimensional creep curve
// F/(mu F3) = 1 - (1 - xi/xi_sat)^2 once its flexibility fits the linear slope; in between, bound
// weight moves from the leading towards the trailing side. The default 0.45 (the flat optimum is
// 0.45-0.5) minimises the largest creep-force error against the exact solver on Hertzian ellipses
// a/b = 0.1 ... 10: 3.0 % instead of 6.2 % with the parabola (docs/FASTSIM.md "Traction bound").
// The shape is concave for skew in [0, 1], the accepted range.
struct TractionBound {
  double skew = 0.45;
  static constexpr TractionBound parabolic() { return {0.0}; }  // Eq 1
};

struct FastSimResult {
  TangentialForces forces;
  // Per contact element, in the order of patch.elements().indices():
  std::vector<double> p1_Pa, p2_Pa;  // tangential traction on the wheel
  std::vector<std::uint8_t> slip;    // 1 where the traction bound mu p3e is active (Eq 8)
  double adhesion_fraction = 1.0;    // elements in adhesion / elements in contact (= area fraction)
};

// FastSim prepared for one contact patch: the traction bound and the marching geometry are
// computed once, so each evaluation costs only the marching. Immutable after construction;
// copies share the prepared data; evaluations are thread-safe.
class FastSim {
 public:
  // Throws railcontact::Error if the patch has no element in contact or bound.skew is not in
  // [0, 1].
  explicit FastSim(const ContactPatch& patch, TractionBound bound = {});

  // Forces only (no per-element output is allocated). Throws railcontact::Error unless mu > 0,
  // L1, L2, L3 > 0 (all finite) and the creepages are finite.
  [[nodiscard]] TangentialForces forces(const Creepage& creepage, const Flexibility& flexibility, double mu) const;
  // Forces, tractions, slip flags. Same checks as forces().
  [[nodiscard]] FastSimResult solve(const Creepage& creepage, const Flexibility& flexibility, double mu) const;

  [[nodiscard]] std::size_t element_count() const;
  [[nodiscard]] TractionBound bound() const;
  // The bound's pressure p3e (Pa) per contact element (patch order; Eq 1 for skew 0): the bound
  // on |p| is mu p3e.
  [[nodiscard]] const std::vector<double>& bound_pressure_Pa() const;
  // S D B of Eq 19: (F1, F2, M3) of FastSim's full-adhesion traction with L1 = L2 = L3 = 1
  // (units N, N, N m per unit creepage per Pa/m of 1/L), column j for creepage j (xi, eta,
  // phi). Without slip FastSim gives F = (S D B) diag(1/L1, 1/L2, 1/L3) (xi, eta, phi).
  [[nodiscard]] const Eigen::Matrix3d& adhesion_force_matrix() const;

  struct Layout;  // the marching data, lane-interleaved (fastsim.cpp)

 private:
  std::shared_ptr<const Layout> layout_;
};

// One-shot conveniences (prepare, then evaluate once).
FastSimResult fastsim(const ContactPatch& patch, const Creepage& creepage, const Flexibility& flexibility, double mu);
TangentialForces fastsim_forces(const ContactPatch& patch, const Creepage& creepage, const Flexibility& flexibility,
                                double mu);

// How nH-FastSim's flexibilities are matched to K2 (paper §2.3; METHOD.md §7 Decision).
enum class FlexibilityMatch {
  // L1 = S(DB)_11 / K2_11 (F1 per xi), L2 = S(DB)_22 / K2_22 (F2 per eta),
  // L3 = S(DB)_23 / K2_23 (F2 per phi, as Kalker's L3 comes from C23). Reproduces K2_11, K2_22
  // and K2_23 exactly in the small-creepage limit. The default.
  term_by_term,
  // Eq 21: L = S K2^-1 D B, its diagonal entries (the paper found it inaccurate).
  full_matrix,
  // As term_by_term, but L3 = S(DB)_33 / K2_33 (M3 per phi).
  spin_from_moment,
};

// nH-FastSim flexibilities (m/Pa) from the full-adhesion creepage matrix K2 (Eq 18, Kalker's
// sign convention, as returned by solve_full_adhesion) of the same patch. Throws
// railcontact::Error if K2 is not finite or a resulting flexibility is not positive and finite
// (e.g. K2_23 of the wrong sign), or, for full_matrix, if K2 is singular.
Flexibility nh_fastsim_flexibility(const FastSim& fastsim, const Eigen::Matrix3d& K2,
                                   FlexibilityMatch match = FlexibilityMatch::term_by_term);
Flexibility nh_fastsim_flexibility(const ContactPatch& patch, const Eigen::Matrix3d& K2,
                                   FlexibilityMatch match = FlexibilityMatch::term_by_term);
// The adhesion options nH-FastSim uses for its flexibilities: the two force rows of K2 by
// adjoint solves (CreepageMatrixPart::force_rows), GMRES tolerance 1e-3 (K2 to ~5e-4, far below
// the flexibilities' discretisation error of about 1 %).
AdhesionOptions nh_fastsim_adhesion_options();

// nH-FastSim flexibilities computed on the patch coarsened by `factor` (coarsened(), patch.hpp):
// about factor^2 fewer elements, so K2 costs about 5x less for factor 2; with at least 250 coarse
// elements the flexibilities differ from the fine patch's by ~1 % (L1, L2) and ~2-4 % (L3) on
// the S1002/UIC60 patches, and the largest creep-force error against `exact` moves by at most
// 0.1 points (docs/FASTSIM.md "Flexibilities on a coarser patch").
Flexibility nh_fastsim_flexibility_coarsened(const ContactPatch& patch, int factor,
                                             const AdhesionOptions& options = nh_fastsim_adhesion_options());

// The coarsening factor railcontact's case runs use unless told otherwise: the largest factor
// (at most 8) that leaves the coarse patch at least 250 elements, and at least 2 from 400
// elements in contact. Measured on the S1002/UIC60 sweep (docs/FASTSIM.md "Flexibilities on a
// coarser patch"): flexibilities from >= 250 coarse elements change nH-FastSim's largest
// creep-force error by at most 0.1 points at 1000-8000 elements in contact, and below 1000
// elements FastSim's own discretisation error dominates (5.3 % at 500 elements, coarsened or
// not). K2 then costs about the same at any patch size (about 0.3-1 ms).
int automatic_flexibility_coarsening(const ContactPatch& patch);

// The same with K2 = solve_full_adhesion(patch.elements(), patch.material(), options).
Flexibility nh_fastsim_flexibility(const ContactPatch& patch, const AdhesionOptions& options = nh_fastsim_adhesion_options(),
                                   FlexibilityMatch match = FlexibilityMatch::term_by_term);

}  // namespace railcontact
