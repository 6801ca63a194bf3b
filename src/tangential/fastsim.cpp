// FastSim on a regular mesh: Kalker's strip marching with the traction bound (paper Eq 1-3,
// 7-8; METHOD.md §7), vectorised across strip runs.
//
// Data layout. The march along a run is sequential (each element starts from the previous,
// possibly limited, traction), so the runs are marched in lock-step, kLanes runs at a time, one
// SIMD lane per run. The runs are sorted by length (longest first) and grouped in blocks of
// kLanes; a block has as many steps as its longest run, and shorter runs are padded at their
// leading side with empty slots (step 0, bound 0: the traction stays 0 there). Slot
// (block, step j, lane r) holds the j-th element, counted from the leading side, of the block's
// r-th run; a block's slots are contiguous, step after step (structure of arrays, aligned).
#include "railcontact/tangential.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <new>
#include <numeric>
#include <string>

#include <fmt/format.h>

// GCC 12's AVX-512 intrinsics (used by <experimental/simd>) trigger a spurious -Wuninitialized
// on _mm512_undefined_pd (GCC PR 105593, fixed in GCC 13).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
#include <experimental/simd>
#pragma GCC diagnostic pop

#include "railcontact/error.hpp"
#include "tangential/fastsim_strips.hpp"
#include "tangential/full_slip.hpp"
#include "tangential/matrix3_eigen.hpp"

namespace railcontact {
namespace {

namespace stdx = std::experimental;

// Two native vectors per lane group (16 doubles with AVX-512): two independent dependency
// chains per step hide the latency of the sqrt/div of the limiting (Eq 8).
constexpr std::size_t kLanes = 2 * stdx::native_simd<double>::size();

// The march with everything it calls inlined (see march); not in an AddressSanitizer build, where
// inlining every instrumented call made this file take 3.8 minutes and 2 GB to compile (24 s
// without), for a speed nobody measures there.
#if defined(__has_feature)
#define RAILCONTACT_ASAN_FEATURE __has_feature(address_sanitizer)
#else
#define RAILCONTACT_ASAN_FEATURE 0
#endif
#if defined(__SANITIZE_ADDRESS__) || RAILCONTACT_ASAN_FEATURE
#define RAILCONTACT_MARCH_INLINED
#else
#define RAILCONTACT_MARCH_INLINED [[gnu::flatten]]
#endif
using Lanes = stdx::fixed_size_simd<double, kLanes>;
constexpr std::size_t kAlignment = 64;  // bytes: one cache line, one AVX-512 vector

// Minimal allocator for cache-line aligned arrays (aligned SIMD loads and stores).
template <class T>
struct AlignedAllocator {
  using value_type = T;
  AlignedAllocator() = default;
  template <class U>
  explicit AlignedAllocator(const AlignedAllocator<U>& /*other*/) {}
  T* allocate(std::size_t n) { return static_cast<T*>(::operator new(n * sizeof(T), std::align_val_t{kAlignment})); }
  void deallocate(T* p, std::size_t /*n*/) { ::operator delete(p, std::align_val_t{kAlignment}); }
  template <class U>
  bool operator==(const AlignedAllocator<U>& /*other*/) const { return true; }
};
template <class T>
using AlignedVector = std::vector<T, AlignedAllocator<T>>;

}  // namespace

struct detail::FastSimLayout {
  std::size_t element_count = 0;
  double element_area_m2 = 0.0;
  std::size_t blocks = 0;
  std::vector<std::size_t> block_first_slot;  // per block; slot of (step 0, lane 0)
  std::vector<std::size_t> block_steps;       // per block
  // Per slot (padding: 0):
  AlignedVector<double> step_m;               // x1 step from the upstream point (fastsim_strips.hpp)
  AlignedVector<double> x1_m;                 // element centre
  AlignedVector<double> bound_Pa;             // bound pressure p3e (Eq 1 or its skewed form)
  std::vector<std::size_t> slot_element;      // element position in patch order; element_count for padding
  AlignedVector<double> lane_x2_m;            // per block and lane: the run's x2
  std::vector<int> lane_strip;                // per block and lane: the run's strip (mesh column; padding 0)
  int strips = 0;                             // mesh columns
  double strip_x2_first_m = 0.0, strip_dx2_m = 0.0;  // x2 of the strips (mesh.x2)
  double reach_m = 0.0;                       // largest |x1|, |x2| of an element edge (overflow check)
  // Patch order:
  TractionBound bound;
  std::vector<double> bound_pressure_Pa;
  Matrix3 adhesion_force_matrix;              // S D B (Eq 19)
  std::shared_ptr<const FullSlip> full_slip;  // SlipDirection::elastic_slip only (full_slip.hpp)
};

namespace {

// Per-element output of a recorded march, in patch order, with one extra element at the end that
// receives the padding slots.
struct MarchRecord {
  std::vector<double> p1_Pa, p2_Pa;
  std::vector<std::uint8_t> slip;
  std::size_t slipping = 0;
};

// Coefficients of the adhesion increments (Eq 2-3): xi/L1, eta/L2 (Pa/m), phi/L3 (Pa/m^2); and
// the weights of the flexibility-weighted slip direction (limit_weighted): with L_min the
// smaller and L_mean the mean of L1 and L2, sigma = L_min / L_mean, rho_i = L_min / L_i, all in
// (0, 1].
// SlipDirection::rigid_slip: the step's spin part taken with L1, L2 instead of L3 is
// dp1 + rigid_d1 (−x2) step, dp2 + rigid_d2 step (x1 − step/2) (Eq 2-3), rigid_d1 = phi (1/L1 − 1/L3),
// rigid_d2 = phi (1/L2 − 1/L3); with a creepage coupling (CreepageCoupling: the increments from the
// effective creepages xi', eta') also the constant parts rigid_c1 step, rigid_c2 step, rigid_c1 =
// (xi − xi')/L1, rigid_c2 = (eta − eta')/L2, which turn a sliding traction to the rigid slip of the
// creepages themselves.
struct MarchCoefficients {
  double xi_over_L1, eta_over_L2, phi_over_L3;
  double sigma, rho1, rho2;
  double rigid_d1 = 0.0, rigid_d2 = 0.0;
  double rigid_c1 = 0.0, rigid_c2 = 0.0;
};

// Per block and lane, the increments' coefficients of a march on strip creepages
// (FastSim::solve(StripCreepages, ...)): dp1 = c1 step, dp2 = c2 step + c3 step (x1 − step/2).
// With SlipDirection::rigid_slip, d1, d2 and d3 the same increments' rigid-slip corrections per
// lane: (xi − xi0) (1/L1 − 1/L3) + (xi − xi')/L1, (eta − eta')/L2 and phi (1/L2 − 1/L3) (xi', eta'
// the strip's effective creepages of a CreepageCoupling; d2 multiplies the step).
struct StripLaneCoefficients {
  AlignedVector<double> c1, c2, c3, d1, d2, d3;
};

// Eq 7-8: a trial traction h = (p1, p2) over the bound (lanes `slip`, |h| > limit) is brought
// back onto |p| = limit.
//  - radial (Eq 8): p = limit h / |h|.
//  - flexibility-weighted: FastSim's elastic law u_i = L_i p_i and Coulomb's law (the traction
//    opposite to the slip, which is the displacement short of adhesion, L (h - p)) ask for
//    p parallel to L (h - p), |p| = limit, i.e. p_i = lambda L_i h_i / (1 + lambda L_i) with the
//    lambda > 0 that puts p on the bound. lambda from the same condition with L1 = L2 = L_mean,
//    lambda L_mean = limit / (|h| - limit), gives, after scaling by (1 + 1/(lambda L_1))
//    (1 + 1/(lambda L_2)) / (1 + 1/(lambda L_mean)) and by sigma (which keep the direction and
//    every factor in (0, 1]),
//      p parallel to v = (h1 (sigma w + (1 - w) rho2), h2 (sigma w + (1 - w) rho1)),  w = limit / |h|,
//    scaled onto the bound: radial at the onset of slip (w -> 1) and for L1 = L2, parallel to
//    (L1 h1, L2 h2) in deep slip (w -> 0), which is the rigid slip's direction for pure
//    creepage. Within 0.15 % of mu F3 of the exact lambda on the S1002/UIC60 flange patches
//    (docs/FASTSIM.md "The slip direction"). Computed as |h| v = h (|h| rho' + limit (sigma - rho')),
//    rho' = (rho2, rho1): one division, as Eq 8 has; |v|^2 is floored so that a bound below
//    ~1e-150 Pa cannot give 0 / 0.
// limit_weighted works on one native vector of lanes (the march splits its lanes in halves: the
// whole group's temporaries would not fit the vector registers).
using Native = stdx::native_simd<double>;
inline void limit_weighted(Native& p1, Native& p2, const Native& norm2, const Native& limit,
                           const typename Native::mask_type& slip, const MarchCoefficients& k) {
  const Native h_norm = stdx::sqrt(norm2);
  const Native m1 = p1 * (h_norm * k.rho2 + limit * (k.sigma - k.rho2));
  const Native m2 = p2 * (h_norm * k.rho1 + limit * (k.sigma - k.rho1));
  const Native floor(std::numeric_limits<double>::min());
  const Native scale = limit / stdx::sqrt(stdx::max(m1 * m1 + m2 * m2, floor));
  stdx::where(slip, p1) = m1 * scale;
  stdx::where(slip, p2) = m2 * scale;
}

// SlipDirection::rigid_slip's trial traction for the limiting's direction: the trial h = (p1, p2) with
// the step's spin part moved towards the rigid slip's by w = A / (A + limit), A the increments' sizes
// summed since the lane began to slip (kept in `sliding`, zero where the lane adheres), the
// increments' corrections (d1 step, d3 step (x1 − step/2)) from MarchCoefficients or per lane.
template <typename L>
void towards_rigid_slip(L& h1, L& h2, L& sliding, const L& increment, const L& limit,
                        const typename L::mask_type& slip, const L& d1_step, const L& d3_step) {
  L grown = sliding + increment;
  sliding = 0.0;
  stdx::where(slip, sliding) = grown;
  const L w = sliding / (sliding + limit);
  h1 += w * d1_step;
  h2 += w * d3_step;
}

// The march of every run (Eq 2-3 increments, Eq 7-8 limit), forces summed per Eq 13:
// F1 = S sum p1, F2 = S sum p2, M3 = S sum (x1 p2 - x2 p1).
// kRecord: the tractions and slip flags of every element into record (and the slipping count);
// kCount: only the count of slipping elements into record->slipping (the adhesion fraction).
// kWeighted: the flexibility-weighted limiting (else radial); kRigid (with kWeighted): its direction
// turned towards the rigid slip's as the lane slides (SlipDirection::rigid_slip).
// kStrips: the coefficients per lane from `strips` (strip creepages; kSpin must be set).
// strip_sums (with kStrips): S sum p1 and S sum p2 of each strip (mesh column) added to [0] and [1].
// RAILCONTACT_MARCH_INLINED (flatten): GCC leaves the 16-lane group's arithmetic (fixed_size_simd)
// as out-of-line calls otherwise; inlined, the rigid-slip march is 3.7 times as fast
// (docs/BENCHMARKS.md "FastSim's march inlined").
template <bool kSpin, bool kWeighted, bool kRecord, bool kCount = kRecord, bool kStrips = false, bool kRigid = false>
RAILCONTACT_MARCH_INLINED TangentialForces march(const detail::FastSimLayout& layout, const MarchCoefficients& k,
                                                 double mu, MarchRecord* record,
                                                 const StripLaneCoefficients* strips = nullptr,
                                                 std::array<double*, 2> strip_sums = {}) {
  static_assert(!kRigid || (kWeighted && kSpin));
  Lanes F1 = 0.0, F2 = 0.0, M3 = 0.0;
  const double* step_m = layout.step_m.data();
  const double* x1_m = layout.x1_m.data();
  const double* bound_Pa = layout.bound_Pa.data();
  const std::size_t* slot_element = layout.slot_element.data();
  for (std::size_t b = 0; b < layout.blocks; ++b) {
    const Lanes x2(&layout.lane_x2_m[b * kLanes], stdx::vector_aligned);
    // dp1 = (xi/L1 - phi x2/L3) step: one coefficient per lane (Eq 2).
    Lanes c1 = kSpin ? Lanes(k.xi_over_L1) - k.phi_over_L3 * x2 : Lanes(k.xi_over_L1);
    Lanes c2 = k.eta_over_L2, c3 = k.phi_over_L3;
    if constexpr (kStrips) {
      c1 = Lanes(&strips->c1[b * kLanes], stdx::vector_aligned);
      c2 = Lanes(&strips->c2[b * kLanes], stdx::vector_aligned);
      c3 = Lanes(&strips->c3[b * kLanes], stdx::vector_aligned);
    }
    // rigid_slip's corrections of the increments (zero unless kRigid) and the lanes' sliding.
    Lanes d1 = -k.rigid_d1 * x2 + k.rigid_c1, d2 = k.rigid_c2, d3 = k.rigid_d2, sliding = 0.0;
    if constexpr (kStrips && kRigid) {
      d1 = Lanes(&strips->d1[b * kLanes], stdx::vector_aligned);
      d2 = Lanes(&strips->d2[b * kLanes], stdx::vector_aligned);
      d3 = Lanes(&strips->d3[b * kLanes], stdx::vector_aligned);
    }
    Lanes p1 = 0.0, p2 = 0.0, sum_p1 = 0.0, sum_p2 = 0.0, sum_x1p2 = 0.0;
    const std::size_t end = layout.block_first_slot[b] + layout.block_steps[b] * kLanes;
    for (std::size_t s = layout.block_first_slot[b]; s < end; s += kLanes) {
      const Lanes step(step_m + s, stdx::vector_aligned);
      const Lanes x1(x1_m + s, stdx::vector_aligned);
      const Lanes limit = mu * Lanes(bound_Pa + s, stdx::vector_aligned);  // mu p3e
      p1 += c1 * step;
      if constexpr (kSpin) {
        // dp2 = (eta/L2) step + (phi/L3) (x1^2 - x1_upstream^2)/2   (Eq 3; fastsim_strips.hpp)
        p2 += c2 * step + c3 * (step * (x1 - 0.5 * step));
      } else {
        p2 += k.eta_over_L2 * step;
      }
      // Eq 7-8: |p| <= mu p3e, else p is brought back onto the bound.
      const Lanes norm2 = p1 * p1 + p2 * p2;
      const auto slip = norm2 > limit * limit;
      if constexpr (kWeighted) {
        static_assert(kLanes == 2 * Native::size());
        if (stdx::any_of(slip)) {
          Lanes h1 = p1, h2 = p2, h_norm2 = norm2;
          if constexpr (kRigid) {
            const Lanes d1_step = d1 * step, d3_step = d2 * step + d3 * (step * (x1 - 0.5 * step));
            const Lanes i1 = c1 * step + d1_step, i2 = c2 * step + c3 * (step * (x1 - 0.5 * step)) + d3_step;
            towards_rigid_slip(h1, h2, sliding, stdx::sqrt(i1 * i1 + i2 * i2), limit, slip, d1_step, d3_step);
            h_norm2 = h1 * h1 + h2 * h2;
          }
          auto [p1a, p1b] = stdx::split<Native>(h1);
          auto [p2a, p2b] = stdx::split<Native>(h2);
          const auto [na, nb] = stdx::split<Native>(h_norm2);
          const auto [la, lb] = stdx::split<Native>(limit);
          const auto [sa, sb] = stdx::split<Native::mask_type>(slip);
          limit_weighted(p1a, p2a, na, la, sa, k);
          limit_weighted(p1b, p2b, nb, lb, sb, k);
          stdx::where(slip, p1) = stdx::concat(p1a, p1b);
          stdx::where(slip, p2) = stdx::concat(p2a, p2b);
        } else if constexpr (kRigid) {
          sliding = 0.0;
        }
      } else {
        const Lanes scale = limit / stdx::sqrt(norm2);  // used in the slipping lanes only
        stdx::where(slip, p1) *= scale;
        stdx::where(slip, p2) *= scale;
      }
      if constexpr (kRecord) {  // scatter to patch order
        alignas(kAlignment) double q1[kLanes], q2[kLanes];
        p1.copy_to(q1, stdx::vector_aligned);
        p2.copy_to(q2, stdx::vector_aligned);
        for (std::size_t r = 0; r < kLanes; ++r) {
          const std::size_t e = slot_element[s + r];
          record->p1_Pa[e] = q1[r];
          record->p2_Pa[e] = q2[r];
          record->slip[e] = slip[r] ? 1 : 0;
        }
      }
      if constexpr (kCount) record->slipping += static_cast<std::size_t>(stdx::popcount(slip));  // padding never slips
      sum_p1 += p1;
      sum_p2 += p2;
      sum_x1p2 += x1 * p2;
    }
    F1 += sum_p1;
    F2 += sum_p2;
    M3 += sum_x1p2 - x2 * sum_p1;  // x2 is constant along a run
    if constexpr (kStrips) {
      if (strip_sums[0] != nullptr) {  // padding lanes add zero to strip 0
        alignas(kAlignment) double q1[kLanes], q2[kLanes];
        sum_p1.copy_to(q1, stdx::vector_aligned);
        sum_p2.copy_to(q2, stdx::vector_aligned);
        for (std::size_t r = 0; r < kLanes; ++r) {
          const auto strip = static_cast<std::size_t>(layout.lane_strip[b * kLanes + r]);
          strip_sums[0][strip] += layout.element_area_m2 * q1[r];
          strip_sums[1][strip] += layout.element_area_m2 * q2[r];
        }
      }
    }
  }
  const double S = layout.element_area_m2;
  return {S * stdx::reduce(F1), S * stdx::reduce(F2), S * stdx::reduce(M3)};
}

bool positive_finite(double value) { return std::isfinite(value) && value > 0.0; }

MarchCoefficients checked_coefficients(const Creepage& creepage, const Flexibility& flexibility, double mu,
                                        const CreepageCoupling& coupling = {}) {
  require(positive_finite(mu),
          [&] { return fmt::format("fastsim: the friction coefficient mu = {} must be positive and finite", mu); });
  require(positive_finite(flexibility.L1) && positive_finite(flexibility.L2) && positive_finite(flexibility.L3), [&] {
    return fmt::format("fastsim: the flexibilities L1 = {}, L2 = {}, L3 = {} m/Pa must be positive and finite",
                       flexibility.L1, flexibility.L2, flexibility.L3);
  });
  require(std::isfinite(creepage.xi) && std::isfinite(creepage.eta) && std::isfinite(creepage.phi), [&] {
    return fmt::format("fastsim: the creepages xi = {}, eta = {}, phi = {} 1/m must be finite", creepage.xi,
                       creepage.eta, creepage.phi);
  });
  // Beyond L_max / L_min = 1e6 (no physical patch) the weighted limiting keeps the radial direction.
  const double L_min = std::min(flexibility.L1, flexibility.L2);
  const double L_max = std::max(flexibility.L1, flexibility.L2);
  const Creepage effective = coupling.effective(creepage);
  MarchCoefficients k{effective.xi / flexibility.L1, effective.eta / flexibility.L2, effective.phi / flexibility.L3,
                      1.0, 1.0, 1.0};
  if (L_max <= 1e6 * L_min) {
    k.sigma = L_min / (0.5 * (flexibility.L1 + flexibility.L2));
    k.rho1 = L_min / flexibility.L1;
    k.rho2 = L_min / flexibility.L2;
  }
  k.rigid_d1 = creepage.phi * (1.0 / flexibility.L1 - 1.0 / flexibility.L3);
  k.rigid_d2 = creepage.phi * (1.0 / flexibility.L2 - 1.0 / flexibility.L3);
  k.rigid_c1 = (creepage.xi - effective.xi) / flexibility.L1;
  k.rigid_c2 = (creepage.eta - effective.eta) / flexibility.L2;
  return k;
}

// The march squares the tractions (Eq 8): they must stay far below sqrt(DBL_MAX) ~ 1.3e154 Pa, or
// p1^2 + p2^2 overflows and the limiting turns the traction into 0 or NaN (L = 1e-300 m/Pa gave
// zero forces). Along a run of length <= 2R (R the reach of the patch) the increments of Eq 2-3
// add up to at most (|xi/L1| + |phi/L3| R) 2R and (|eta/L2| + |phi/L3| R) 2R, on top of a traction
// already limited to mu p3e. Real tractions are below ~1e11 Pa; 1e150 only refuses inputs of
// non-physical magnitude (kind invalid_input).
void require_marchable(const MarchCoefficients& k, double reach_m, const Creepage& creepage,
                       const Flexibility& flexibility) {
  // The spin's increments with the largest of 1/L1, 1/L2, 1/L3: rigid_slip turns them from L3 to L1, L2.
  const double phi_over_L = std::fabs(creepage.phi) *
                            std::max({1.0 / flexibility.L1, 1.0 / flexibility.L2, 1.0 / flexibility.L3});
  const double bound_Pa =
      (std::fabs(k.xi_over_L1) + std::fabs(k.eta_over_L2) + 2.0 * phi_over_L * reach_m) * 2.0 * reach_m;
  require(bound_Pa <= 1e150, [&] {
    return fmt::format("fastsim: the creepages xi = {:g}, eta = {:g}, phi = {:g} 1/m over the flexibilities L1 = {:g}, "
                       "L2 = {:g}, L3 = {:g} m/Pa give adhesion tractions up to {:g} Pa on this patch, beyond the "
                       "1e150 Pa FastSim can march: the flexibilities are not physical",
                       creepage.xi, creepage.eta, creepage.phi, flexibility.L1, flexibility.L2, flexibility.L3,
                       bound_Pa);
  });
}

// Which limiting a march takes: flexibility-weighted (also rigid_slip's) unless L1 = L2, where it
// is the radial one, which is cheaper; rigid_slip's turn towards the rigid slip where its
// corrections are not zero (spin, or strips of several ξ, and L3 other than L1 or L2).
struct Limiting {
  bool weighted, rigid;
};
// The slip directions whose march turns a sliding traction to the rigid slip (elastic_slip marches
// as rigid_slip, then blends in the full-slip state).
bool marches_to_rigid_slip(SlipDirection d) {
  return d == SlipDirection::rigid_slip || d == SlipDirection::elastic_slip;
}

Limiting limiting(const detail::FastSimLayout& layout, const MarchCoefficients& k, bool rigid_corrections) {
  const SlipDirection d = layout.bound.slip_direction;
  const bool rigid = marches_to_rigid_slip(d) && rigid_corrections;
  return {rigid || (d != SlipDirection::radial && k.rho1 != k.rho2), rigid};
}

// The march for these creepages and this bound: with or without spin, radial or weighted limiting.
template <bool kRecord, bool kCount = kRecord>
TangentialForces march_for(const detail::FastSimLayout& layout, const Creepage& creepage, const MarchCoefficients& k,
                           double mu, MarchRecord* record) {
  const bool spin = creepage.phi != 0.0;
  const Limiting l =
      limiting(layout, k, spin && (k.rigid_d1 != 0.0 || k.rigid_d2 != 0.0 || k.rigid_c1 != 0.0 || k.rigid_c2 != 0.0));
  if (spin) {
    if (l.rigid) return march<true, true, kRecord, kCount, false, true>(layout, k, mu, record);
    return l.weighted ? march<true, true, kRecord, kCount>(layout, k, mu, record)
                      : march<true, false, kRecord, kCount>(layout, k, mu, record);
  }
  const bool weighted = l.weighted;
  return weighted ? march<false, true, kRecord, kCount>(layout, k, mu, record)
                  : march<false, false, kRecord, kCount>(layout, k, mu, record);
}

// With marchable input every step of the march is finite: a non-finite force is a bug (internal).
void require_finite_forces(const TangentialForces& f) {
  if (std::isfinite(f.F1_N) && std::isfinite(f.F2_N) && std::isfinite(f.M3_Nm)) return;
  throw Error(ErrorKind::internal,
              fmt::format("fastsim: non-finite forces F1 = {:g}, F2 = {:g}, M3 = {:g} from checked input; not returned "
                          "(a bug: please report it)",
                          f.F1_N, f.F2_N, f.M3_Nm));
}

// S D B of Eq 19: (F1, F2, M3) of the full-adhesion traction with unit flexibilities, column j
// for unit creepage j, from the march's own increments (fastsim_strips.hpp) over the slot layout,
// a run per lane. The padding slots come before each run's leading element with step 0: they add
// nothing. Unit xi and unit eta march the same p (p1 for xi, p2 for eta), so (S D B)_11 = _22.
Eigen::Matrix3d marched_adhesion_force_matrix(const detail::FastSimLayout& layout) {
  Lanes db11 = 0.0, db31 = 0.0, db32 = 0.0, db13 = 0.0, db23 = 0.0, db33 = 0.0;
  for (std::size_t b = 0; b < layout.blocks; ++b) {
    const Lanes x2(&layout.lane_x2_m[b * kLanes], stdx::vector_aligned);
    Lanes p = 0.0, p1_phi = 0.0, p2_phi = 0.0;  // per unit xi (or eta), per unit phi
    const std::size_t end = layout.block_first_slot[b] + layout.block_steps[b] * kLanes;
    for (std::size_t s = layout.block_first_slot[b]; s < end; s += kLanes) {
      const Lanes step(layout.step_m.data() + s, stdx::vector_aligned);
      const Lanes x1(layout.x1_m.data() + s, stdx::vector_aligned);
      p += step;
      p1_phi -= x2 * step;
      p2_phi += step * (x1 - 0.5 * step);  // (x1^2 - x1_upstream^2)/2
      db11 += p;
      db31 -= x2 * p;
      db32 += x1 * p;
      db13 += p1_phi;
      db23 += p2_phi;
      db33 += x1 * p2_phi - x2 * p1_phi;
    }
  }
  Eigen::Matrix3d DB;
  DB << stdx::reduce(db11), 0.0, stdx::reduce(db13),  //
      0.0, stdx::reduce(db11), stdx::reduce(db23),    //
      stdx::reduce(db31), stdx::reduce(db32), stdx::reduce(db33);
  return layout.element_area_m2 * DB;
}

// A record for a march over n elements, with the padding slots' sink at the end.
MarchRecord empty_record(std::size_t n) {
  return {std::vector<double>(n + 1), std::vector<double>(n + 1), std::vector<std::uint8_t>(n + 1), 0};
}

// A recorded march's result: its forces (checked finite; the tractions sum to them, so they are
// finite with them), the tractions and slip flags without the padding sink, the adhesion fraction.
FastSimResult recorded_result(const TangentialForces& forces, MarchRecord record) {
  require_finite_forces(forces);
  const std::size_t n = record.p1_Pa.size() - 1;
  record.p1_Pa.pop_back();  // drop the padding sink
  record.p2_Pa.pop_back();
  record.slip.pop_back();
  FastSimResult result;
  result.forces = forces;
  result.p1_Pa = std::move(record.p1_Pa);
  result.p2_Pa = std::move(record.p2_Pa);
  result.slip = std::move(record.slip);
  result.adhesion_fraction = static_cast<double>(n - record.slipping) / static_cast<double>(n);
  return result;
}

// SlipDirection::elastic_slip: the march's forces (and tractions, when recorded) moved towards
// Coulomb's law along the elastic slip by the full-slip solver's weight (full_slip.hpp); the
// adhesion fraction scaled by 1 − weight (the slip flags stay the march's).
void blend_full_slip(const detail::FullSlipTractions& full, TangentialForces& forces, double& adhesion_fraction,
                     FastSimResult* fields) {
  if (!(full.weight > 0.0)) return;
  const double w = full.weight;
  forces.F1_N += w * (full.forces.F1_N - forces.F1_N);
  forces.F2_N += w * (full.forces.F2_N - forces.F2_N);
  forces.M3_Nm += w * (full.forces.M3_Nm - forces.M3_Nm);
  adhesion_fraction *= 1.0 - w;
  if (fields != nullptr) {
    for (std::size_t e = 0; e < fields->p1_Pa.size(); ++e) {
      fields->p1_Pa[e] += w * (full.p1_Pa[e] - fields->p1_Pa[e]);
      fields->p2_Pa[e] += w * (full.p2_Pa[e] - fields->p2_Pa[e]);
    }
  }
  require_finite_forces(forces);
}

}  // namespace

const char* slip_direction_name(SlipDirection direction) {
  switch (direction) {
    case SlipDirection::radial: return "radial";
    case SlipDirection::flexibility_weighted: return "flexibility-weighted";
    case SlipDirection::rigid_slip: return "rigid-slip";
    case SlipDirection::elastic_slip: return "elastic-slip";
  }
  return "?";
}

SlipDirection parse_slip_direction(const std::string& name) {
  for (SlipDirection d : {SlipDirection::radial, SlipDirection::flexibility_weighted, SlipDirection::rigid_slip,
                          SlipDirection::elastic_slip})
    if (name == slip_direction_name(d)) return d;
  throw Error(
      fmt::format("unknown slip direction '{}' (radial, flexibility-weighted, rigid-slip, elastic-slip)", name));
}

FastSim::FastSim(const ContactPatch& patch, TractionBound bound) {
  require(patch.elements().count() > 0, "fastsim: the contact patch has no element in contact");
  require(std::isfinite(bound.skew) && bound.skew >= 0.0 && bound.skew <= 1.0,
          [&] { return fmt::format("fastsim: the traction bound's skew = {} must lie in [0, 1]", bound.skew); });
  require(bound.slip_direction == SlipDirection::radial || bound.slip_direction == SlipDirection::flexibility_weighted ||
              bound.slip_direction == SlipDirection::rigid_slip || bound.slip_direction == SlipDirection::elastic_slip,
          [&] {
            return fmt::format("fastsim: the slip direction {} is not one of radial (0), flexibility-weighted (1), "
                               "rigid-slip (2), elastic-slip (3)",
                               static_cast<int>(bound.slip_direction));
          });
  const Mesh& mesh = patch.mesh();
  auto layout = std::make_shared<detail::FastSimLayout>();
  layout->bound = bound;
  layout->element_count = patch.elements().count();
  layout->element_area_m2 = patch.mesh().element_area_m2();
  layout->bound_pressure_Pa = fastsim_detail::traction_bound_Pa(patch, bound.skew);
  const std::vector<double> step = fastsim_detail::march_steps_m(patch);

  // Runs, longest first (stable: ties keep the patch order).
  const std::vector<StripRun>& runs = patch.runs();
  std::vector<std::size_t> order(runs.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&runs](std::size_t i, std::size_t j) { return runs[i].length() > runs[j].length(); });

  layout->blocks = (runs.size() + kLanes - 1) / kLanes;
  std::size_t slots = 0;
  for (std::size_t b = 0; b < layout->blocks; ++b) {
    const auto steps = static_cast<std::size_t>(runs[order[b * kLanes]].length());
    layout->block_first_slot.push_back(slots);
    layout->block_steps.push_back(steps);
    slots += steps * kLanes;
  }
  layout->step_m.assign(slots, 0.0);
  layout->x1_m.assign(slots, 0.0);
  layout->bound_Pa.assign(slots, 0.0);
  layout->slot_element.assign(slots, layout->element_count);
  layout->lane_x2_m.assign(layout->blocks * kLanes, 0.0);
  layout->lane_strip.assign(layout->blocks * kLanes, 0);
  layout->strips = mesh.n2;
  layout->strip_x2_first_m = mesh.x2_first_m;
  layout->strip_dx2_m = mesh.dx2_m;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    const StripRun& run = runs[order[r]];
    const std::size_t b = r / kLanes, lane = r % kLanes;
    const auto length = static_cast<std::size_t>(run.length());
    const std::size_t pad = layout->block_steps[b] - length;
    layout->lane_x2_m[b * kLanes + lane] = mesh.x2(run.i2);  // = patch.x2(run.first), without a division
    layout->lane_strip[b * kLanes + lane] = run.i2;
    for (std::size_t j = 0; j < length; ++j) {
      const std::size_t e = run.first + length - 1 - j;  // j-th element from the leading edge
      const std::size_t s = layout->block_first_slot[b] + (pad + j) * kLanes + lane;
      layout->step_m[s] = step[e];
      layout->x1_m[s] = mesh.x1(run.i1_leading - static_cast<int>(j));  // = patch.x1(e)
      layout->bound_Pa[s] = layout->bound_pressure_Pa[e];
      layout->slot_element[s] = e;
    }
  }
  // The largest |x1|, |x2| of an element edge: the runs' end elements bound |x1|.
  for (const StripRun& run : runs)
    layout->reach_m = std::max({layout->reach_m, std::fabs(mesh.x1(run.i1_trailing)) + 0.5 * mesh.dx1_m,
                                std::fabs(mesh.x1(run.i1_leading)) + 0.5 * mesh.dx1_m,
                                std::fabs(mesh.x2(run.i2)) + 0.5 * mesh.dx2_m});
  layout->adhesion_force_matrix = detail::to_matrix3(marched_adhesion_force_matrix(*layout));
  if (bound.slip_direction == SlipDirection::elastic_slip) layout->full_slip = std::make_shared<detail::FullSlip>(patch);
  layout_ = std::move(layout);
}

std::size_t FastSim::element_count() const { return layout_->element_count; }
TractionBound FastSim::bound() const { return layout_->bound; }
const std::vector<double>& FastSim::bound_pressure_Pa() const { return layout_->bound_pressure_Pa; }
const Matrix3& FastSim::adhesion_force_matrix() const { return layout_->adhesion_force_matrix; }

TangentialForces FastSim::forces(const Creepage& creepage, const Flexibility& flexibility, double mu,
                                 const CreepageCoupling& coupling) const {
  if (layout_->full_slip) return forces_and_adhesion(creepage, flexibility, mu, coupling).forces;
  const MarchCoefficients k = checked_coefficients(creepage, flexibility, mu, coupling);
  require_marchable(k, layout_->reach_m, creepage, flexibility);
  const TangentialForces forces = march_for<false>(*layout_, creepage, k, mu, nullptr);
  require_finite_forces(forces);
  return forces;
}

FastSimResult FastSim::forces_and_adhesion(const Creepage& creepage, const Flexibility& flexibility, double mu,
                                           const CreepageCoupling& coupling) const {
  const MarchCoefficients k = checked_coefficients(creepage, flexibility, mu, coupling);
  require_marchable(k, layout_->reach_m, creepage, flexibility);
  MarchRecord count;
  FastSimResult result;
  result.forces = march_for<false, true>(*layout_, creepage, k, mu, &count);
  require_finite_forces(result.forces);
  const std::size_t n = layout_->element_count;
  result.adhesion_fraction = static_cast<double>(n - count.slipping) / static_cast<double>(n);
  if (layout_->full_slip)
    blend_full_slip(layout_->full_slip->solve(creepage, mu, result.adhesion_fraction), result.forces,
                    result.adhesion_fraction, nullptr);
  return result;
}

FastSimResult FastSim::solve(const Creepage& creepage, const Flexibility& flexibility, double mu,
                             const CreepageCoupling& coupling) const {
  const MarchCoefficients k = checked_coefficients(creepage, flexibility, mu, coupling);
  require_marchable(k, layout_->reach_m, creepage, flexibility);
  MarchRecord record = empty_record(layout_->element_count);
  const TangentialForces forces = march_for<true>(*layout_, creepage, k, mu, &record);
  FastSimResult result = recorded_result(forces, std::move(record));
  if (layout_->full_slip)
    blend_full_slip(layout_->full_slip->solve(creepage, mu, result.adhesion_fraction), result.forces,
                    result.adhesion_fraction, &result);
  return result;
}

namespace {

// The march's coefficients for strip creepages (FastSim::solve(StripCreepages, ...)), checked as
// solve() checks one creepage; k receives the coefficients of the largest ones (the limiting's).
StripLaneCoefficients strip_lane_coefficients(const detail::FastSimLayout& layout, const StripCreepages& given,
                                              const Flexibility& flexibility, double mu, MarchCoefficients& k,
                                              const CreepageCoupling& coupling) {
  require(given.size() == static_cast<std::size_t>(layout.strips), [&] {
    return fmt::format("fastsim: {} strip creepages for a patch of {} strips (mesh columns)", given.size(),
                       layout.strips);
  });
  // ξ0: the strips' ξ at x2 = 0, linear between the two strips around it (the patch's origin).
  // Marching every strip's ξ − ξ0 with L3 (as Eq 2 marches −φ x2) is within 4.6 % of μ F3 of the
  // exact solver over the conformal patches of every shipped profile pair; marching the part not
  // linear in x2 with L1 misses by up to 7.8 % (S1002 on the 1:20 rail at y = −6.2 mm).
  const auto xi_at_origin = [&layout](const StripCreepages& strips) {
    if (layout.strips == 1) return strips[0].xi;
    const double at = std::clamp(-layout.strip_x2_first_m / layout.strip_dx2_m, 0.0, layout.strips - 1.0);
    const std::size_t below = std::min(static_cast<std::size_t>(at), static_cast<std::size_t>(layout.strips - 2));
    return strips[below].xi + (at - static_cast<double>(below)) * (strips[below + 1].xi - strips[below].xi);
  };
  // The increments march each strip's effective creepages (CreepageCoupling; the creepages
  // themselves without one): its own eta and phi couple into its xi, and xi0 into its eta, as one
  // creepage (xi0, eta, phi) couples in solve(Creepage) (the strips' xi − xi0 is marched like −phi x2).
  StripCreepages creepages = given;
  if (!coupling.none()) {
    const double given_xi0 = xi_at_origin(given);
    for (Creepage& c : creepages)
      c = {c.xi + coupling.xi_per_eta * c.eta + coupling.xi_per_phi_m * c.phi,
           c.eta + coupling.eta_per_xi * given_xi0 + coupling.eta_per_phi_m * c.phi, c.phi};
  }
  // The largest creepages check the flexibilities, mu and the march's range as solve() does.
  Creepage largest;
  for (const Creepage& c : creepages) {
    require(std::isfinite(c.xi) && std::isfinite(c.eta) && std::isfinite(c.phi), [&] {
      return fmt::format("fastsim: the strip creepages xi = {}, eta = {}, phi = {} 1/m must be finite", c.xi, c.eta,
                         c.phi);
    });
    largest = {std::max(largest.xi, std::fabs(c.xi)), std::max(largest.eta, std::fabs(c.eta)),
               std::max(largest.phi, std::fabs(c.phi))};
  }
  k = checked_coefficients(largest, flexibility, mu);
  require_marchable(k, layout.reach_m, largest, flexibility);
  const double xi0 = xi_at_origin(creepages);
  StripLaneCoefficients lanes;
  lanes.c1.resize(layout.lane_strip.size());
  lanes.c2.resize(layout.lane_strip.size());
  lanes.c3.resize(layout.lane_strip.size());
  const bool rigid = marches_to_rigid_slip(layout.bound.slip_direction);
  if (rigid) {
    lanes.d1.resize(layout.lane_strip.size());
    lanes.d2.resize(layout.lane_strip.size());
    lanes.d3.resize(layout.lane_strip.size());
  }
  for (std::size_t l = 0; l < layout.lane_strip.size(); ++l) {
    const Creepage& c = creepages[static_cast<std::size_t>(layout.lane_strip[l])];
    const Creepage& own = given[static_cast<std::size_t>(layout.lane_strip[l])];
    lanes.c1[l] = xi0 / flexibility.L1 + (c.xi - xi0) / flexibility.L3;
    lanes.c2[l] = c.eta / flexibility.L2;
    lanes.c3[l] = c.phi / flexibility.L3;
    if (rigid) {
      lanes.d1[l] = (c.xi - xi0) * (1.0 / flexibility.L1 - 1.0 / flexibility.L3) + (own.xi - c.xi) / flexibility.L1;
      lanes.d2[l] = (own.eta - c.eta) / flexibility.L2;
      lanes.d3[l] = c.phi * (1.0 / flexibility.L2 - 1.0 / flexibility.L3);
    }
  }
  return lanes;
}

}  // namespace

FastSimResult FastSim::solve(const StripCreepages& creepages, const Flexibility& flexibility, double mu,
                             const CreepageCoupling& coupling) const {
  const detail::FastSimLayout& layout = *layout_;
  MarchCoefficients k{};
  const StripLaneCoefficients lanes = strip_lane_coefficients(layout, creepages, flexibility, mu, k, coupling);
  MarchRecord record = empty_record(layout.element_count);
  const Limiting l = limiting(layout, k, !lanes.d1.empty());
  const TangentialForces forces = l.rigid      ? march<true, true, true, true, true, true>(layout, k, mu, &record, &lanes)
                                  : l.weighted ? march<true, true, true, true, true>(layout, k, mu, &record, &lanes)
                                               : march<true, false, true, true, true>(layout, k, mu, &record, &lanes);
  FastSimResult result = recorded_result(forces, std::move(record));
  if (layout.full_slip)
    blend_full_slip(layout.full_slip->solve(creepages, mu, result.adhesion_fraction), result.forces,
                    result.adhesion_fraction, &result);
  return result;
}

StripForces FastSim::strip_forces(const StripCreepages& creepages, const Flexibility& flexibility, double mu,
                                  const CreepageCoupling& coupling) const {
  const detail::FastSimLayout& layout = *layout_;
  MarchCoefficients k{};
  const StripLaneCoefficients lanes = strip_lane_coefficients(layout, creepages, flexibility, mu, k, coupling);
  StripForces out;
  out.F1_N.assign(creepages.size(), 0.0);
  out.F2_N.assign(creepages.size(), 0.0);
  const std::array<double*, 2> sums{out.F1_N.data(), out.F2_N.data()};
  const Limiting l = limiting(layout, k, !lanes.d1.empty());
  MarchRecord count;
  out.forces = l.rigid      ? march<true, true, false, true, true, true>(layout, k, mu, &count, &lanes, sums)
               : l.weighted ? march<true, true, false, true, true>(layout, k, mu, &count, &lanes, sums)
                            : march<true, false, false, true, true>(layout, k, mu, &count, &lanes, sums);
  require_finite_forces(out.forces);
  const std::size_t n = layout.element_count;
  out.adhesion_fraction = static_cast<double>(n - count.slipping) / static_cast<double>(n);
  if (layout.full_slip) {
    const detail::FullSlipTractions full = layout.full_slip->solve(creepages, mu, out.adhesion_fraction);
    if (full.weight > 0.0) {
      // Each strip's sums blended as the forces are.
      const ContactPatch& patch = layout.full_slip->patch();
      const auto n1 = static_cast<std::size_t>(patch.mesh().n1);
      const double area = patch.mesh().element_area_m2();
      std::vector<double> F1(out.F1_N.size(), 0.0), F2(out.F2_N.size(), 0.0);
      for (std::size_t e = 0; e < full.p1_Pa.size(); ++e) {
        const std::size_t strip = patch.elements().indices()[e] / n1;
        F1[strip] += area * full.p1_Pa[e];
        F2[strip] += area * full.p2_Pa[e];
      }
      for (std::size_t j = 0; j < F1.size(); ++j) {
        out.F1_N[j] += full.weight * (F1[j] - out.F1_N[j]);
        out.F2_N[j] += full.weight * (F2[j] - out.F2_N[j]);
      }
    }
    blend_full_slip(full, out.forces, out.adhesion_fraction, nullptr);
  }
  return out;
}

FastSimResult fastsim(const ContactPatch& patch, const Creepage& creepage, const Flexibility& flexibility, double mu) {
  return FastSim(patch).solve(creepage, flexibility, mu);
}

TangentialForces fastsim_forces(const ContactPatch& patch, const Creepage& creepage, const Flexibility& flexibility,
                                double mu) {
  return FastSim(patch).forces(creepage, flexibility, mu);
}

}  // namespace railcontact
