#pragma once
// Coulomb's law along the elastic slip where a patch slips everywhere (SlipDirection::elastic_slip;
// docs/FASTSIM.md "Where the exact solver slips everywhere: the elastic slip").
//
// In full slip every element's traction is −mu p3 s/|s| with the slip s = w − R p (docs/METHOD.md
// §6: w the rigid slip, R the steady-rolling operator, p the traction on the wheel). That state
// solves the exact problem whenever it exists (the solution is unique), and it is found by a fixed
// point e = R p(e), p(e) = −mu p3 (w − e)/|w − e|, on a coarse copy of the patch:
//   p_0 = −mu p3 w/|w|,   e_1 = R p_0,   e_k+1 = e_k + r f_k − (ΔE + r ΔF) γ_k,   f_k = R p(e_k) − e_k,
// r = 1/2, with Anderson's mixing over the last three steps (ΔE, ΔF: the differences of the
// iterates and of their residuals; γ_k fits f_k by ΔF in least squares): at most eight products of R
// (FFT), fewer once it has settled (full_slip.cpp), the elastic slip e of the last one
// interpolated bilinearly onto the marched patch's elements, whose tractions then follow w − e.
// Where the patch keeps an adhesion zone no full-slip state exists and the iterate does not
// settle; a weight in [0, 1] says how far its result can be trusted, and FastSim blends its own
// march into it:
//   weight = S((0.3 − a)/0.1) S((0.08 − dF)/0.065),
// S(t) the smoothstep on [0, 1], a the march's adhesion fraction (the iteration runs only below
// 0.3), dF the largest change of the coarse forces over mu F3 in the last three steps (settled:
// below 0.015). Where the exact solver slips everywhere, or keeps an adhesion zone of a few tenths
// of a percent (at a spin's pole inside the patch), the iterate settles; as the adhesion zone
// grows it wanders, and dF with it (docs/FASTSIM.md).
#include <memory>
#include <mutex>
#include <vector>

#include "railcontact/contact_patch.hpp"

namespace railcontact {
class InfluenceOperator;
}

namespace railcontact::detail {

struct FullSlipTractions {
  double weight = 0.0;               // of these tractions against the march's, in [0, 1]
  int products = 0;                  // of R the iteration took (at most 8; fewer once settled)
  TangentialForces forces;           // of p1_Pa, p2_Pa (M3 about the patch's origin, as FastSim's)
  std::vector<double> p1_Pa, p2_Pa;  // per element of the marched patch, patch order (weight > 0)
};

// One patch's full-slip solver. Immutable after construction but for the coarse copy and its
// operator's kernels, made on first use (thread-safe); solves are thread-safe.
class FullSlip {
 public:
  explicit FullSlip(const ContactPatch& patch);
  ~FullSlip();
  FullSlip(const FullSlip&) = delete;
  FullSlip& operator=(const FullSlip&) = delete;

  // The adhesion fraction of FastSim's march below which the iteration runs; above it the weight
  // is 0 and nothing is computed.
  static constexpr double kAdhesionFractionFrom = 0.3;

  [[nodiscard]] const ContactPatch& patch() const { return patch_; }

  // The full-slip tractions for one creepage, or for strip creepages (one per mesh column of the
  // patch: w = (xi_j, eta_j + phi_j x1), linear between the strips at a coarse element's x2), with
  // the march's adhesion fraction. Weight 0 (and no tractions) where the iteration is not to be
  // trusted.
  [[nodiscard]] FullSlipTractions solve(const Creepage& creepage, double mu, double adhesion_fraction) const;
  [[nodiscard]] FullSlipTractions solve(const StripCreepages& creepages, double mu, double adhesion_fraction) const;

 private:
  struct Coarse;
  ContactPatch patch_;
  mutable std::once_flag made_;
  mutable std::unique_ptr<Coarse> coarse_;
  const Coarse& coarse() const;

  template <typename RigidSlip>
  FullSlipTractions solve_with(const RigidSlip& rigid_slip, double mu, double adhesion_fraction) const;
};

}  // namespace railcontact::detail
