#pragma once
// Stage: tangential problem. Full adhesion and the creepage matrix K2 (Eq 10-18), FastSim on a
// regular mesh (Eq 1-9), nH-FastSim (Eq 19-21) and the exact steady-rolling solvers with Coulomb
// friction (Appendix, Eq A1). docs/ADHESION.md, docs/FASTSIM.md, docs/ROLLING.md.
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "railcontact/contact_patch.hpp"
#include "railcontact/kalker.hpp"

// Full-adhesion steady-state rolling on an arbitrary set of contact elements (paper §2.2,
// Eq 10-18; METHOD.md §6): the non-Hertzian analogue of Kalker's linear theory.
//
// Steady rolling in +X1 (leading edge at the largest x1): the slip velocity at the collocation
// points is s = V (w - R p), R the upwind X1-difference of the tangential influence (the
// paper's (A - A0)/dx1 of Eq 10) and w = (xi - phi x2, eta + phi x1) the rigid slip (Eq 11-12).
// Full adhesion, s = 0: R p = D^T (xi, eta, phi)  (Eq 14), and the creepage-coefficient matrix
//   K2 = S D R^-1 D^T  (Eq 18),  (F1, F2, M3) = K2 (xi, eta, phi)  (Eq 13, 15).
// With this sign convention K2 has the pattern of Kalker's K1 (Eq 16): negative diagonal.
// Coordinates are the mesh's: put the origin at the pressure centre (METHOD.md §2).


namespace railcontact {

// The tangential models of a patch, one name each for the command line, case files, the wheelset,
// the C API (rc_method) and Python (METHODS): nH-FastSim (NhFastSim), classic FastSim with the
// equivalent ellipse's flexibilities (FastSim, Eq 9), and the exact solver with its regularised
// variant (solve_rolling_exact, solve_rolling_regularised).
// Each model is prepared and solved behind one seam, TangentialModel (railcontact/tangential_model.hpp).
// The C API's rc_method values are these enumerators' values.
enum class TangentialSolver { nh_fastsim, fastsim, exact, exact_regularised };
inline constexpr std::array<TangentialSolver, 4> kTangentialSolvers{
    TangentialSolver::nh_fastsim, TangentialSolver::fastsim, TangentialSolver::exact,
    TangentialSolver::exact_regularised};
// "nh-fastsim", "fastsim", "exact", "exact-regularised"
const char* solver_name(TangentialSolver solver);
// Throws Error (invalid_input) naming the allowed names.
TangentialSolver parse_tangential_solver(const std::string& name);
// The solver of an integer value (the C API's rc_method); throws Error (invalid_input) "<what> =
// <value> is not <kind> (0 nh-fastsim, 1 fastsim, 2 exact, 3 exact-regularised)".
TangentialSolver tangential_solver_of(int value, std::string_view what, std::string_view kind = "a tangential solver");

enum class LinearSolver {
  krylov,  // GMRES on the FFT operator, preconditioned by strip marching (fast path)
  dense,   // dense LU (reference path; O(N^3))
};

// Where the rigid slip w is evaluated along X1 for each element.
enum class RigidSlipPoint {
  collocation,         // at the collocation point x1 + alpha dx1/2 (the paper)
  difference_centre,   // at the centre of the upwind difference, x1 + (alpha + 1) dx1/2
};

// What to compute of K2.
enum class CreepageMatrixPart {
  full,        // all of K2 and the tractions: one direct solve R p = D^T e_j per creepage (3 solves)
  // Rows 1 and 2 (F1 and F2 per unit xi, eta, phi) by adjoint solves R^T y = (S D)^T e_i, one per
  // force (2 solves): all term-by-term nH-FastSim needs (K2_11, K2_22, K2_23) and the
  // normalisation of Eq 22-23 (f11, f22). Row 3 (M3) is NaN and no tractions are returned.
  force_rows,
};

// The smallest collocation offset alpha the solvers accept (docs/ROLLING.md "Options"). alpha = -1
// centres the upwind difference on the element and makes R singular; approaching it, R's
// condition grows like 1/(1 + alpha): GMRES needs about 70 iterations per solve at alpha = -0.9,
// 115 at -0.95, 240 at -0.98 and 400 (the default limit) at -0.99, on ellipses of 700 to 11000
// elements alike, and fails from -0.995; the exact solver needs 18 Newton steps at -0.95, 40-50 at
// -0.97 ... -0.99 and does not converge from -0.995. -0.95 keeps a factor 3.5 below the limits.
inline constexpr double kMinimumCollocationOffset = -0.95;

struct AdhesionOptions {
  double collocation_offset = 0.0;  // alpha in [-0.95, 1]: collocation point at x1 + alpha dx1/2 (METHOD.md §3)
  // Collocation offset for the spin column of K2 only (unit phi); unset = collocation_offset.
  // The paper (Fig 3) finds alpha = 0 best for C11, C22 and alpha = 0.5 best for C23; each
  // column of K2 is a separate solve, so each may use its own offset.
  std::optional<double> spin_collocation_offset;
  RigidSlipPoint rigid_slip_point = RigidSlipPoint::collocation;
  LinearSolver solver = LinearSolver::krylov;
  double tolerance = 1e-10;         // Krylov: relative residual, in (0, 1e-2]
  int max_iterations = 400;         // Krylov, positive
  CreepageMatrixPart part = CreepageMatrixPart::full;
};

// A 3 × 3 matrix of doubles (the creepage matrix K2, FastSim's S D B): m(i, j) is row i, column j,
// counted from 0.
struct Matrix3 {
  std::array<double, 9> values{};  // row by row
  [[nodiscard]] double operator()(int i, int j) const { return values[static_cast<std::size_t>(3 * i + j)]; }
  double& operator()(int i, int j) { return values[static_cast<std::size_t>(3 * i + j)]; }
  [[nodiscard]] bool all_finite() const {
    for (double v : values)
      if (!std::isfinite(v)) return false;
    return true;
  }
};

// Tractions (Pa) per unit creepage: 2N rows [p1 on elements 0..N-1, p2 on elements 0..N-1] in the
// order of ContactElements::indices(), one column per creepage (xi, eta, phi).
struct UnitTractions {
  std::size_t rows = 0;
  std::vector<double> values;  // column by column: (row, j) at values[j rows + row]
  [[nodiscard]] double operator()(std::size_t row, int column) const {
    return values[static_cast<std::size_t>(column) * rows + row];
  }
  [[nodiscard]] bool all_finite() const {
    for (double v : values)
      if (!std::isfinite(v)) return false;
    return true;
  }
};

struct AdhesionSolution {
  // (F1, F2, M3) = K2 (xi, eta, phi): units N, N, N m per unit xi, eta and per 1/m of phi.
  Matrix3 creepage_matrix;
  UnitTractions unit_tractions;  // empty for CreepageMatrixPart::force_rows
  int iterations = 0;               // Krylov iterations, all three right-hand sides
  double relative_residual = 0.0;   // largest over the right-hand sides
};

// Throws railcontact::Error on bad input (kind invalid_input: no elements, bad material, alpha
// outside [kMinimumCollocationOffset, 1] = [-0.95, 1], tolerance outside (0, 1e-2], a
// non-positive iteration limit), when the Krylov solver does not converge (not_converged), and
// with kind internal if K2 or the tractions come out non-finite (with valid input an invariant of
// the solver is broken; nothing non-finite is returned).
AdhesionSolution solve_full_adhesion(const ContactElements& elements, const Material& material,
                                     const AdhesionOptions& options = {});

// Kalker's creepage coefficients from K2 with c = sqrt(a b) (paper §3, METHOD.md §2):
// C11 = -K2_11/(G c^2), C22 = -K2_22/(G c^2), C23 = -K2_23/(G c^3), C33 = -K2_33/(G c^4).
struct CreepageCoefficients {
  double C11 = 0.0, C22 = 0.0, C23 = 0.0, C33 = 0.0;
};
CreepageCoefficients creepage_coefficients(const Matrix3& creepage_matrix, double shear_modulus_Pa, double c_m);

}  // namespace railcontact

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
//     increment of Eq 2-3 between the two centres; a sum over the bound is brought back onto
//     |p| = mu p3e (Eq 7-8: scaled, or optionally turned towards the slip of FastSim's elastic
//     law, SlipDirection below), and the limited traction is the start of the next increment
//     (Kalker's FASTSIM). Elements where the limit is active slip.
// For pure creepage (phi = 0) this equals element-wise clipping of Eq 2-3; with spin it does not.


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
//
// A traction h over the bound (|h| > mu p3e) slips, and the traction is brought back onto the bound
// in the direction SlipDirection chooses (docs/FASTSIM.md "The slip direction"):
//  - radial: h scaled onto the bound (Eq 8, Kalker's FASTSIM and the paper);
//  - flexibility_weighted (the wheelset's default, WheelsetOptions::nh_fastsim): opposite to the
//    slip of FastSim's own elastic law u_i = L_i p_i, i.e. p parallel to L (h - p) with
//    L = diag(L1, L2) (Coulomb's law in that law), in closed form. The same as radial when L1 = L2;
//    in deep slip the traction follows the rigid slip, where the radial one follows (xi/L1, eta/L2).
//    With nH-FastSim on the flange at y = -7 mm it takes the F1 error from -3.2 to -0.6 % of mu F3;
//    it costs ~3x the march time in slip, and raises the paper's Fig 5 errors by 0.05-0.09 points
//    on single patches, which keep radial (docs/FASTSIM.md "The slip direction").
//  - rigid_slip: flexibility_weighted, with the rigid slip's own spin
//    taking over as an element slides. nH-FastSim's L3 (from K2's spin coupling) marches the spin
//    (and on a conformal patch the strips' ξ variation) with a flexibility other than L1, L2: in
//    adhesion that is the fit, but in deep slip the traction then follows (ξ − φ x2 L1/L3,
//    η + φ x1 L2/L3), not the rigid slip (ξ − φ x2, η + φ x1) Coulomb's law asks for. Here the
//    slipping traction's direction takes the step's spin part with L1, L2 instead of L3 in
//    proportion A / (A + mu p3e), A the adhesion increments |dp| summed since the element's strip
//    began to slip (the sliding so far, in traction units): FastSim's own law at the onset of slip,
//    the rigid slip's where the strip has slid far beyond its elastic range. Without spin (and
//    strips of one ξ) it is flexibility_weighted. On the shipped profile pairs' flange patches in
//    full slip under spin it takes nH-FastSim from 30.5 % to 2.9 % of mu F3 of the exact solver
//    (docs/FASTSIM.md "The slip direction").
//  - elastic_slip (the wheelset's default): rigid_slip, and where the patch slips everywhere the
//    tractions of Coulomb's law along the elastic slip s = w − R p (w the rigid slip, R the
//    steady-rolling operator; docs/METHOD.md §6), solved on a coarse copy of the patch by a fixed
//    point with Anderson's mixing, at most eight products of R (src/tangential/full_slip.hpp). The
//    march's result moves to them by a weight in [0, 1] that is 0 unless the march's adhesion
//    fraction is below 0.3 and rises as the fixed point settles (1 where its forces changed by less than 0.015
//    of mu F3 over its last three steps, 0 from 0.08): continuous in the creepages. Only the
//    creepages and the patch enter, not the flexibilities. On the steep flange patches that slip
//    everywhere under spin it takes nH-FastSim from up to 7.3 % to within 0.5 % of mu F3 of the
//    exact solver, and at the onset of full slip on flange roots from up to 3.6 % to within 0.9 %
//    (docs/FASTSIM.md "The elastic slip where a patch slips everywhere"); it costs about 0.2 ms per
//    flange patch on the fly and 0.1 ms per table node where it runs, nothing elsewhere
//    (docs/BENCHMARKS.md "The elastic slip where a patch slips everywhere"). The slip flags stay
//    the march's; the adhesion fraction is scaled by 1 − weight.
enum class SlipDirection { radial, flexibility_weighted, rigid_slip, elastic_slip };
// "radial", "flexibility-weighted", "rigid-slip", "elastic-slip"; parse_slip_direction throws invalid_input for
// other names.
const char* slip_direction_name(SlipDirection direction);
SlipDirection parse_slip_direction(const std::string& name);
struct TractionBound {
  double skew = 0.45;
  SlipDirection slip_direction = SlipDirection::radial;
  // The paper's nH-FastSim and Kalker's FastSim: the parabola of Eq 1, limited by Eq 8.
  static constexpr TractionBound parabolic() { return {0.0, SlipDirection::radial}; }
};

// FastSim's forces on a patch and, per strip (mesh column), the sums S Σ p1 and S Σ p2 (N) of its
// elements' tractions.
struct StripForces {
  TangentialForces forces;
  std::vector<double> F1_N, F2_N;  // per strip: its tractions times the element area (N)
  double adhesion_fraction = 0.0;  // elements in adhesion / elements in contact
};

struct FastSimResult {
  TangentialForces forces;
  // Per contact element, in the order of patch.elements().indices():
  std::vector<double> p1_Pa, p2_Pa;  // tangential traction on the wheel
  std::vector<std::uint8_t> slip;    // 1 where the traction bound mu p3e is active (Eq 8)
  double adhesion_fraction = 1.0;    // elements in adhesion / elements in contact (= area fraction)
};

namespace detail {
struct FastSimLayout;  // the marching data, lane-interleaved (fastsim.cpp)
}  // namespace detail

// The part of K2's force rows that FastSim's diagonal flexibilities leave out (docs/FASTSIM.md
// "The creepage coupling"). In adhesion FastSim's F1 comes from xi and the spin only, F2 from eta
// and the spin, and the spin's F1 from the spin's flexibility L3 (matched to K2_23, not K2_13). On a
// patch that is not symmetric about its axes (a comet, a flange) K2 also carries F1 per eta (K2_12),
// F2 per xi (K2_21) and another F1 per spin. FastSim marches the effective creepages
//   xi' = xi + xi_per_eta eta + xi_per_phi_m phi,   eta' = eta + eta_per_xi xi + eta_per_phi_m phi,
// phi' = phi, with which its full-adhesion F1 and F2 are K2's first two rows entire:
//   xi_per_eta = K2_12 / K2_11,  xi_per_phi_m = (K2_13 - S(DB)_13 / L3) / K2_11,
//   eta_per_xi = K2_21 / K2_22,  eta_per_phi_m = (K2_23 - S(DB)_23 / L3) / K2_22 (0 term by term).
// All zero: FastSim's own creepages (the paper's method; flexibilities given without a coupling).
// In FastSim's march (FastSim::solve(..., coupling)) the effective creepages give the adhesion
// increments; with SlipDirection::rigid_slip a sliding traction still turns to the rigid slip of the
// creepages themselves.
struct CreepageCoupling {
  double xi_per_eta = 0.0;      // -
  double xi_per_phi_m = 0.0;    // m
  double eta_per_xi = 0.0;      // -
  double eta_per_phi_m = 0.0;   // m
  [[nodiscard]] Creepage effective(const Creepage& c) const {
    return {c.xi + xi_per_eta * c.eta + xi_per_phi_m * c.phi, c.eta + eta_per_xi * c.xi + eta_per_phi_m * c.phi, c.phi};
  }
  [[nodiscard]] bool none() const {
    return xi_per_eta == 0.0 && xi_per_phi_m == 0.0 && eta_per_xi == 0.0 && eta_per_phi_m == 0.0;
  }
  // What a table may hold: the ratios within ±1 and the lengths within ±0.1 m (measured on the
  // shipped pairs: ratios below 0.01, lengths below 1 mm).
  [[nodiscard]] bool plausible() const {
    return std::abs(xi_per_eta) <= 1.0 && std::abs(eta_per_xi) <= 1.0 && std::abs(xi_per_phi_m) <= 0.1 &&
           std::abs(eta_per_phi_m) <= 0.1;
  }
  // The coupling of the same march on a copy of the patch whose origin lies at (d1, d2) (m) in the
  // patch's coordinates, the creepages taken there: FastSim marches the spin with L3, so where L1
  // or L2 differ from L3 its spin terms depend on the origin, and
  //   xi_per_phi_m' = xi_per_phi_m + d2 (1 - L1/L3) - xi_per_eta d1,
  //   eta_per_phi_m' = eta_per_phi_m + eta_per_xi d2 - d1 (1 - L2/L3)
  // keep its full-adhesion forces. No coupling stays none.
  [[nodiscard]] CreepageCoupling moved_to(double d1_m, double d2_m, const Flexibility& L) const;
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
  // L1, L2, L3 > 0 (all finite) and the creepages are finite, and when the adhesion tractions
  // (creepage / L times the patch length) would exceed 1e150 Pa, beyond what the march can square
  // (non-physical flexibilities; kind invalid_input). A non-finite result is never returned (kind
  // internal: with checked input it would be a bug).
  [[nodiscard]] TangentialForces forces(const Creepage& creepage, const Flexibility& flexibility, double mu,
                                        const CreepageCoupling& coupling = {}) const;
  // Forces, tractions, slip flags. Same checks as forces().
  [[nodiscard]] FastSimResult solve(const Creepage& creepage, const Flexibility& flexibility, double mu,
                                    const CreepageCoupling& coupling = {}) const;
  // Forces and the adhesion fraction only (p1_Pa, p2_Pa, slip left empty): the cost of forces(),
  // for a caller that needs the adhesion fraction but not the fields. Same checks as forces().
  [[nodiscard]] FastSimResult forces_and_adhesion(const Creepage& creepage, const Flexibility& flexibility,
                                                  double mu, const CreepageCoupling& coupling = {}) const;
  // Forces, tractions, slip flags from the creepages of each strip (StripCreepages: one per mesh
  // column; a conformal patch, docs/METHOD.md "nH-FastSim on a conformal patch"). Each strip
  // marches dp1 = (ξ0/L1 + (ξ_i2 − ξ0)/L3) step and dp2 = (η_i2/L2) step + (φ_i2/L3) step (x1 −
  // step/2), ξ0 the strips' ξ at x2 = 0 (linear between the two strips around it): the variation of
  // ξ across the strips marches with the spin's flexibility, as −φ x2 does in Eq 2, so the strips
  // (ξ − φ x2, η, φ) give solve(ξ, η, φ)'s numbers. Throws Error (invalid_input) for another count
  // or a non-finite creepage, and as solve().
  [[nodiscard]] FastSimResult solve(const StripCreepages& creepages, const Flexibility& flexibility, double mu,
                                    const CreepageCoupling& coupling = {}) const;
  // The same march, forces only, with each strip's sums (what a conformal patch turns strip by
  // strip into its frame): no per-element output is allocated. Same checks as solve().
  [[nodiscard]] StripForces strip_forces(const StripCreepages& creepages, const Flexibility& flexibility,
                                         double mu, const CreepageCoupling& coupling = {}) const;

  [[nodiscard]] std::size_t element_count() const;
  [[nodiscard]] TractionBound bound() const;
  // The bound's pressure p3e (Pa) per contact element (patch order; Eq 1 for skew 0): the bound
  // on |p| is mu p3e.
  [[nodiscard]] const std::vector<double>& bound_pressure_Pa() const;
  // S D B of Eq 19: (F1, F2, M3) of FastSim's full-adhesion traction with L1 = L2 = L3 = 1
  // (units N, N, N m per unit creepage per Pa/m of 1/L), column j for creepage j (xi, eta,
  // phi). Without slip FastSim gives F = (S D B) diag(1/L1, 1/L2, 1/L3) (xi, eta, phi).
  [[nodiscard]] const Matrix3& adhesion_force_matrix() const;

 private:
  std::shared_ptr<const detail::FastSimLayout> layout_;
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
// sign convention, as returned by solve_full_adhesion) of the patch FastSim was prepared on
// (Eq 19-20, or Eq 21 for full_matrix). The building block of NhFastSim; throws
// railcontact::Error if K2 is not finite or a resulting flexibility is not positive and finite
// (e.g. K2_23 of the wrong sign), or, for full_matrix, if K2 is singular.
Flexibility nh_fastsim_flexibility(const FastSim& fastsim, const Matrix3& K2,
                                   FlexibilityMatch match = FlexibilityMatch::term_by_term);

// The recipe of nH-FastSim (docs/FASTSIM.md, docs/METHOD.md §7).
struct NhFastSimOptions {
  // FastSim's traction bound: railcontact's skewed bound by default, TractionBound::parabolic()
  // for the paper's Eq 1.
  TractionBound bound{};
  // The flexibilities come from K2 of the patch coarsened in square blocks of this factor
  // (coarsened(); 1: the patch itself, up to kMaximumCoarsening); 0: automatic,
  // NhFastSim::automatic_coarse_blocks (one element longer across than along from factor 3).
  int flexibility_coarsening = 0;
  // alpha of K2's collocation points (docs/METHOD.md §3), in [kMinimumCollocationOffset, 1].
  double collocation_offset = 0.0;
  FlexibilityMatch match = FlexibilityMatch::term_by_term;
  // March the effective creepages of K2's coupling (CreepageCoupling) in adhesion (recipe 4: the
  // wheelset's default, WheelsetOptions::nh_fastsim); false (single patches' default): the paper's
  // method, F1 from xi and the spin only, F2 from eta and the spin (docs/FASTSIM.md "The creepage
  // coupling").
  bool creepage_coupling = false;
};

// The coupling of K2 (its force rows, Kalker's sign convention) that FastSim prepared on the patch
// K2 was solved on leaves out with the flexibilities L (nh_fastsim_flexibility). Throws
// railcontact::Error if the force rows are not finite.
CreepageCoupling creepage_coupling(const FastSim& fastsim, const Matrix3& K2, const Flexibility& L);

// The flexibilities of nH-FastSim and the creepage coefficients of the K2 they were matched to:
// f11 = -K2_11 (F1 per unit xi), f22 = -K2_22, f23 = -K2_23 (N, N, N m), which also normalise the
// creepages of the paper's study (Eq 22-23).
struct NhFastSimFlexibilities {
  Flexibility flexibility;
  double f11_N = 0.0, f22_N = 0.0, f23_Nm = 0.0;
  CreepageCoupling coupling;  // K2's coupling (above); zero for the paper's method
};

// The version of the recipe by which NhFastSim's first constructor (below) computes the
// flexibilities by default (automatic coarse blocks, K2's solves), recorded in flexibility and
// wheelset tables so that a table built with an older one can be told apart: its flexibilities
// are not the ones computed on the fly today.
//   1: square blocks f x f, K2 to GMRES 1e-3 (until 2026-11-26);
//   2: blocks f x (f + 1) from f = 3 (2026-11-26; docs/FASTSIM.md "Blocks one element longer across");
//   3: K2 to GMRES 3e-3 (2026-11-26; docs/FASTSIM.md "K2's solves");
//   4: the creepage coupling of K2's force rows (docs/FASTSIM.md "The creepage coupling").
inline constexpr int kNhFastSimRecipe = 4;
// The recipe these options compute: kNhFastSimRecipe, or 3 without the creepage coupling.
constexpr int nh_fastsim_recipe(bool creepage_coupling) { return creepage_coupling ? kNhFastSimRecipe : 3; }

// nH-FastSim prepared for one contact patch: the whole method in one place. On the fly (the first
// constructor) it
//   1. coarsens the patch for the adhesion solve (NhFastSimOptions::flexibility_coarsening),
//   2. solves the two force rows of K2 on it by adjoint GMRES solves to 3e-3 (Eq 18; the entries
//      the match uses to ~3e-3, below the flexibilities' discretisation error of ~1 %),
//   3. matches FastSim's full-adhesion forces on that patch to K2 term by term (Eq 19-20): L1-L3,
//   4. prepares FastSim with the traction bound on the patch itself (Eq 1 or the skewed bound),
// and each evaluation is FastSim's march (Eq 2-8). The second constructor takes flexibilities
// computed elsewhere (a flexibility table) and skips 1-3. Immutable after construction;
// evaluations are thread-safe; copies share the prepared FastSim.
class NhFastSim {
 public:
  // Throws Error for bad options or when the adhesion solve or the match fails (Error kinds
  // not_converged / invalid_input).
  explicit NhFastSim(const ContactPatch& patch, const NhFastSimOptions& options = {});
  // With given flexibilities (no K2): options.bound is used, the rest of the options is ignored.
  NhFastSim(const ContactPatch& patch, const NhFastSimFlexibilities& given, const NhFastSimOptions& options = {});

  // The largest factor (at most kMaximumCoarsening) that leaves the coarse patch at least 250
  // elements, and at least 2 from 400 elements in contact (docs/FASTSIM.md "Flexibilities on a
  // coarser patch": from about 250 coarse elements the largest creep-force error moves by at most
  // 0.1 points; below 1000 elements FastSim's own discretisation error dominates).
  static int automatic_coarsening(const ContactPatch& patch);
  // The blocks of the automatic coarsening: automatic_coarsening(patch) = f elements along the
  // rolling direction and, from f = 3, f + 1 across (f below). With the lateral direction one
  // element coarser the paper's Fig 5 errors are lower at most sizes from 2000 elements (their rms
  // nearly everywhere; docs/FASTSIM.md "Blocks one element longer across"), and K2 costs 40 %
  // less at ~4700 elements (a power-of-two transform length across).
  static CoarseBlocks automatic_coarse_blocks(const ContactPatch& patch);

  // Creep forces and the spin moment on the wheel (Kalker's sign convention). Throws Error unless
  // mu > 0 and the creepages are finite.
  [[nodiscard]] TangentialForces forces(const Creepage& creepage, double mu) const;
  // Forces, tractions and slip flags per contact element (patch order).
  [[nodiscard]] FastSimResult solve(const Creepage& creepage, double mu) const;
  // The same from the creepages of each strip (FastSim::solve(StripCreepages, ...)).
  [[nodiscard]] FastSimResult solve(const StripCreepages& creepages, double mu) const;
  // Forces and the adhesion fraction only (FastSim::forces_and_adhesion).
  [[nodiscard]] FastSimResult forces_and_adhesion(const Creepage& creepage, double mu) const;

  // Raw creepages from the normalised ones of the paper's study (Eq 22-23):
  // xi = xi' 3 mu F3 / f11, eta = eta' 3 mu F3 / f22; phi as given (1/m).
  [[nodiscard]] Creepage creepage_from_normalised(double xi_normalised, double eta_normalised, double phi_per_m,
                                                  double mu, double normal_force_N) const;

  [[nodiscard]] const NhFastSimFlexibilities& flexibilities() const { return flexibilities_; }
  [[nodiscard]] const Flexibility& flexibility() const { return flexibilities_.flexibility; }
  [[nodiscard]] const CreepageCoupling& coupling() const { return flexibilities_.coupling; }
  // K2 of the coarsened patch as solved (rows 1-2; row 3 NaN with the term-by-term match), when
  // computed on the fly.
  [[nodiscard]] const std::optional<Matrix3>& creepage_matrix() const { return creepage_matrix_; }
  // The coarsening used for K2: its blocks, and coarsening() their length along the rolling
  // direction (0 when the flexibilities were given).
  [[nodiscard]] CoarseBlocks coarse_blocks() const { return coarse_blocks_; }
  [[nodiscard]] int coarsening() const { return coarse_blocks_.along; }
  [[nodiscard]] int krylov_iterations() const { return krylov_iterations_; }
  [[nodiscard]] const FastSim& fastsim() const { return fastsim_; }

 private:
  NhFastSim(FastSim fastsim, NhFastSimFlexibilities flexibilities, std::optional<Matrix3> K2,
            CoarseBlocks coarse_blocks, int krylov_iterations);
  FastSim fastsim_;
  NhFastSimFlexibilities flexibilities_;
  std::optional<Matrix3> creepage_matrix_;
  CoarseBlocks coarse_blocks_{0, 0};
  int krylov_iterations_ = 0;
};

// nH-FastSim on a patch of one or several connected lobes (docs/WHEELSET.md §8). A merged
// wheel–rail patch, such as the tread and the flange root of S1002 on UIC60 at y = −4.6 … −5.7 mm,
// holds two lobes 10–20 mm apart: one set of flexibilities for both, from K2 of the whole patch,
// misses the exact forces by up to 6.9 % of μF3. Here each lobe (a 4-neighbour connected set of
// elements, contact_regions) gets its own flexibilities, from K2 of that lobe coarsened as a patch
// of its own, and the creepages at its own centre of pressure; the lobes' elastic coupling is
// neglected, as FastSim neglects it within a patch. A patch of one lobe is plain NhFastSim.
//
// The patch's mesh coordinates minus its shift (ContactPatch::x1_shift_m) are those of the mesh it
// was cut from: a lobe coarsened by its automatic factor is cropped in whole blocks counted from
// that mesh's origin (a wheel–rail patch's reference point), as the patch itself was. A lobe of
// fewer than 20 elements (just appeared: too few for K2) takes the flexibilities of its equivalent
// ellipse (Eq 9) with nH-FastSim's traction bound. Immutable after construction; solves are
// thread-safe.
class NhFastSimPerLobe {
 public:
  // Whether the patch's elements form more than one lobe, or two joined by a neck (then it is
  // worth more than NhFastSim).
  [[nodiscard]] static bool has_several_lobes(const ContactPatch& patch);

  // Throws Error as NhFastSim does (for a lobe of 200 elements or more whose K2 fails).
  explicit NhFastSimPerLobe(const ContactPatch& patch, const NhFastSimOptions& options = {});
  NhFastSimPerLobe(const NhFastSimPerLobe&);
  NhFastSimPerLobe(NhFastSimPerLobe&&) noexcept;
  NhFastSimPerLobe& operator=(const NhFastSimPerLobe&);
  NhFastSimPerLobe& operator=(NhFastSimPerLobe&&) noexcept;
  ~NhFastSimPerLobe();

  // Forces and spin moment about the patch's origin (its centre of pressure), for the creepages
  // there; tractions and slip flags per element of the patch (patch order), adhesion fraction over
  // the whole patch. Throws Error unless mu > 0 and the creepages are finite.
  [[nodiscard]] FastSimResult solve(const Creepage& creepage, double mu) const;
  // The same from the creepages of each strip (one per column of the patch's mesh, the rigid slip of
  // an element at x1 of strip j being (ξ_j, η_j + φ_j x1) from the patch's origin: a conformal
  // patch, docs/WHEELSET.md §4): each lobe marches its own columns' strips, η_j moved to its centre.
  // Throws Error for another count of strips or a non-finite creepage, and as solve().
  [[nodiscard]] FastSimResult solve(const StripCreepages& creepages, double mu) const;

  [[nodiscard]] std::size_t lobe_count() const;
  // Lobe k (by decreasing load): its patch (the crop nH-FastSim solved, origin at its centre of
  // pressure), its flexibilities (Eq 9 of its equivalent ellipse for a lobe too small for K2) and
  // its centre of pressure in the patch's coordinates.
  struct LobeView {
    const ContactPatch& patch;
    const Flexibility& flexibility;
    double x1_centre_m, x2_centre_m;
    CreepageCoupling coupling;  // zero for the equivalent ellipse's fallback
  };
  [[nodiscard]] LobeView lobe(std::size_t k) const;
  // The most loaded lobe's flexibilities (those of the patch when it has one lobe).
  [[nodiscard]] const Flexibility& flexibility() const;
  // Its coarsening factor (NhFastSim::coarsening(); 0 for the equivalent-ellipse fallback).
  [[nodiscard]] int coarsening() const;
  // GMRES iterations of all the lobes' K2 solves.
  [[nodiscard]] int krylov_iterations() const;
  // A patch whose neck lies between a quarter and half the width of its lobes is solved both per
  // lobe and whole, the results blended with this weight of the whole patch's (0 otherwise;
  // linear in the neck's ratio, so that the forces do not jump where a widening neck stops being
  // one: src/tangential/cropped_patch.hpp); the whole patch's flexibilities then (else nullptr).
  [[nodiscard]] double whole_patch_weight() const { return whole_weight_; }
  [[nodiscard]] const Flexibility* whole_patch_flexibility() const;
  // The creepage coupling of the most loaded lobe, and of the whole patch where a neck is blended
  // (zero without one, or for the equivalent ellipse's fallback).
  [[nodiscard]] CreepageCoupling coupling() const;
  [[nodiscard]] CreepageCoupling whole_patch_coupling() const;

 private:
  struct Lobe;
  // Each lobe's solution from the creepages at its centre (lobe k: `at_lobe(lobe)`), summed.
  template <typename CreepagesAtLobe>
  [[nodiscard]] FastSimResult solve_lobes(const CreepagesAtLobe& at_lobe, double mu) const;
  [[nodiscard]] FastSimResult blended_with_whole(FastSimResult per_lobe, const FastSimResult& whole) const;
  std::vector<Lobe> lobes_;
  std::vector<Lobe> whole_;  // the whole patch, when blended (at most one)
  double whole_weight_ = 0.0;
  std::size_t patch_elements_ = 0;
  // The patch's columns in the coordinates of the mesh it was cut from (first centre, count, size).
  double source_x2_first_m_ = 0.0, dx2_m_ = 0.0;
  int columns_ = 0;
};

}  // namespace railcontact

// Exact steady-state rolling with Coulomb friction on a contact patch (paper §2.2 and Appendix;
// METHOD.md §8): the reference the simplified methods are measured against.
//
// Slip per unit rolling speed at the collocation points: s = w - R p (Eq 10, sign derived in
// docs/CONVENTIONS.md), w = (xi - phi x2, eta + phi x1). Two friction laws:
//  - exact Coulomb: adhesion where |p| < mu p3 and s = 0; slip where |p| = mu p3 and p = -mu p3 s/|s|;
//  - regularised Coulomb (Eq A1): p = -(2 mu p3 / pi) atan(|s|/epsilon) s/|s|.
// Both are solved by Newton's method with GMRES on the FFT operator (docs/ROLLING.md).


namespace railcontact {

// Ranges of RollingOptions (validate(RollingOptions); docs/ROLLING.md "Options").
// regularisation: epsilon is a slip per unit rolling speed. The law reaches 99.4 % of mu p3 at
// |s| = 100 epsilon, so at 1e-2 only at a slip of 1 (a locked wheel): beyond, no creepage a
// rolling wheel can have approaches Coulomb's law, and at 1e10 the forces vanish (1e200 gave NaN
// reported as converged). Below 1e-14 nothing changes (the forces equal the exact solver's to six
// digits from 1e-10 down) while each decade of the continuation costs ~5 Newton steps, so the
// default budget of 100 runs out near 1e-17: use the exact solver instead.
inline constexpr double kMinimumRegularisation = 1e-14;
inline constexpr double kMaximumRegularisation = 1e-2;
// tolerance (relative to mu max p3): above 1e-3 a "converged" traction may be off by more than
// 0.1 % of the traction bound per element (1 would accept the starting guess).
inline constexpr double kMaximumRollingTolerance = 1e-3;

struct RollingOptions {
  double collocation_offset = 0.0;  // alpha in [-0.95, 1] (METHOD.md §3), the same as the adhesion solver's
  double tolerance = 1e-9;          // Newton: max residual relative to mu max(p3), in (0, 1e-3]
  int max_newton_iterations = 100;  // positive
  double krylov_tolerance = 1e-6;   // inner GMRES, relative, in (0, 0.5]: the tightest one (see inexact_newton)
  int max_krylov_iterations = 300;  // positive
  // Exact solver only: each Newton step's GMRES stops at max(krylov_tolerance, min(residual, 0.1))
  // (inexact Newton; the same converged solution, about half the GMRES iterations); false: every
  // step to krylov_tolerance.
  bool inexact_newton = true;
  // Regularised law only: epsilon as a slip velocity per unit rolling speed (dimensionless;
  // equals the paper's epsilon in m/s at V = 1 m/s), in [1e-14, 1e-2]. The paper uses 1e-8.
  double regularisation = 1e-8;
};

// Throws railcontact::Error (invalid_input) naming the RollingOptions field, its value and its
// range unless every option lies in the range given above (the regularisation is checked whichever
// solver the options are for).
void validate(const RollingOptions& options);

struct RollingSolution {
  TangentialForces forces;
  // Per contact element, in the order of patch.elements().indices():
  std::vector<double> p1_Pa, p2_Pa;     // tangential traction on the wheel
  std::vector<double> s1, s2;           // slip velocity per unit rolling speed (-)
  std::vector<std::uint8_t> slip;       // 1 where the element slips (|p| at the traction bound)
  double adhesion_fraction = 0.0;       // share of the contact area in adhesion
  int newton_iterations = 0;
  int krylov_iterations = 0;            // all inner GMRES iterations
  double residual = 0.0;                // final Newton residual (<= tolerance), relative to mu max(p3)
};

// Throws railcontact::Error on bad input (mu <= 0 or not finite, non-finite creepage, options
// outside their ranges: validate(RollingOptions); kind invalid_input), when Newton does not
// converge within max_newton_iterations or breaks down with a non-finite residual (kind
// not_converged), and with kind internal should a converged solution hold a non-finite number (an
// invariant of the solver broken): a returned solution has converged (residual <= tolerance) and
// every number in it is finite.
RollingSolution solve_rolling_exact(const ContactPatch& patch, const Creepage& creepage, double mu,
                                    const RollingOptions& options = {});
RollingSolution solve_rolling_regularised(const ContactPatch& patch, const Creepage& creepage, double mu,
                                          const RollingOptions& options = {});

// Strip creepages (StripCreepages, railcontact/contact_patch.hpp): one Creepage per mesh column;
// throws Error (invalid_input) for another count or a non-finite creepage.
RollingSolution solve_rolling_exact(const ContactPatch& patch, const StripCreepages& creepages, double mu,
                                    const RollingOptions& options = {});
RollingSolution solve_rolling_regularised(const ContactPatch& patch, const StripCreepages& creepages, double mu,
                                          const RollingOptions& options = {});

}  // namespace railcontact

// Kalker's creepage coefficients computed numerically: K2 (Eq 18) on an elliptical patch on a
// regular mesh, converted with c = sqrt(a b) (paper §3). Compares directly with Kalker's table.


namespace railcontact {

struct EllipseCoefficientOptions {
  int target_elements = 2800;  // about this many elements in contact
  EllipseMeshLayout layout = EllipseMeshLayout::rolling_resolved;
  AdhesionOptions adhesion = default_adhesion_for_coefficients();
  // false: c = sqrt(a b) of the ellipse (the paper). true: c from the discrete patch's area,
  // c^2 = N S / pi, which removes the staircase-area error of the mesh from the comparison.
  bool c_from_discrete_area = false;

  // alpha = 0 for the xi and eta columns, alpha = 0.5 for the spin column (paper Fig 3).
  static AdhesionOptions default_adhesion_for_coefficients() {
    AdhesionOptions options;
    options.spin_collocation_offset = 0.5;
    return options;
  }
};

struct EllipseCoefficientResult {
  CreepageCoefficients coefficients;
  Matrix3 creepage_matrix;
  std::size_t elements_in_contact = 0;
  int n1 = 0, n2 = 0;               // mesh over the bounding box
  double area_error = 0.0;          // (N S - pi a b) / (pi a b)
  int iterations = 0;
  double solve_time_s = 0.0;        // K2 (operator set-up and the three solves)
};

// For semi-axis ratio a/b (a along X1) and Poisson's ratio nu in [0, 0.5]; E = 2.1e11 Pa and
// c = sqrt(a b) = 6 mm (the coefficients do not depend on either).
EllipseCoefficientResult ellipse_creepage_coefficients(double a_over_b, double nu,
                                                       const EllipseCoefficientOptions& options = {});

}  // namespace railcontact
