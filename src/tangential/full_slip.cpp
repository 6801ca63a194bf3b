// Coulomb's law along the elastic slip where a patch slips everywhere (full_slip.hpp).
#include "tangential/full_slip.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <tuple>
#include <utility>

#include <Eigen/Dense>

#include "elastic/influence_operator.hpp"
#include "support/smoothstep.hpp"
#include "tangential/cropped_patch.hpp"

namespace railcontact::detail {
namespace {

// The iteration and its weight (full_slip.hpp), measured on the 1:20 flange at y = −6.5 mm, yaw
// −10 mrad, its creepages scaled by k = 0.10 ... 0.40 in steps of 0.0025, on S1002 on 54E1's flange
// root at −4.9 and −5.0 mm (k = 0.6 ... 1) and on an ellipse with its spin's pole near or inside
// the patch (docs/FASTSIM.md "The elastic slip where a patch slips everywhere"): with Anderson's
// mixing the iterate settles within eight products wherever the exact solver slips everywhere
// (largest change of its last three steps below 0.015 of mu F3), and where an adhesion zone
// grows it wanders (0.05-0.11 from 5 % adhesion up); the weight falls from 1 at 0.015 to 0 at
// 0.08, a band wide enough that the blend moves the forces by at most 1.9 % of mu F3 per step of
// the sweep (k + 0.0025).
constexpr int kProducts = 8;
constexpr int kSettledSteps = 3;
constexpr double kRelaxation = 0.5;                     // the damping r of each step
constexpr int kHistory = 3;                             // Anderson's depth
constexpr double kChangeFrom = 0.08, kChangeTo = 0.015;  // of mu F3: weight 0 above, 1 below
// The iteration stops before its eighth product once it has settled: its last three steps changed
// the forces by less than kChangeTo (so the weight is 1, as the eight would give) and the last two
// by less than kConverged of mu F3. Measured over 2133 solves (the 1:20 flange's k-sweep, 54E1's
// flange root, the flange lookup benchmark's patch at 2 mrad of yaw, creepages scaled): the
// products it leaves out would have moved the coarse forces by at most 4.6e-4 of mu F3, and it
// stops after 5.9 products on average (on that patch the changes run 0.085, 0.0028, 0.0028,
// 0.0005, 1.5e-5: five); on 54E1's flange root the iterate never settles that far. Over the
// shipped profile pairs' 4466 patches nH-FastSim's forces moved by at most 1.3e-3 of mu F3.
constexpr double kConverged = 1e-3;

// Anderson's mixing of the fixed point e = R p(e) (Walker and Ni, SIAM J. Numer. Anal. 49, 2011):
// of the residuals f_i = R p(e_i) − e_i of the last kHistory + 1 iterates, the combination
// sum a_i f_i (sum a_i = 1) smallest over the elements in contact, and the next iterate
// e = sum a_i (e_i + r f_i). With one iterate it is the damped step e ← e + r f. Each step keeps its
// e_i + r f_i and f_i in a ring and adds one row to the residuals' Gram matrix; the fit solves for
// the differences to the newest residual (normal equations of at most kHistory × kHistory).
class Anderson {
 public:
  explicit Anderson(std::size_t size)
      : size_(size),
        mixed_(std::make_unique_for_overwrite<double[]>(kSlots * size)),
        residual_(std::make_unique_for_overwrite<double[]>(kSlots * size)) {}

  // One step from e with the product R p(e), e updated in place. Both hold two components of
  // size_/2 values each, the elements in contact the first `in_contact` of each: the fit runs over
  // those.
  void step(std::vector<double>& e, const std::vector<double>& product, std::size_t in_contact) {
    const std::size_t half = size_ / 2;
    const int s = newest_ = (newest_ + 1) % kSlots;
    used_ = std::min(used_ + 1, kSlots);
    double* f = residual_.get() + s * size_;
    double* g = mixed_.get() + s * size_;
    for (std::size_t at = 0; at < size_; ++at) {
      f[at] = product[at] - e[at];
      g[at] = e[at] + kRelaxation * f[at];
    }
    for (int j = 0; j < used_; ++j) {
      const double* h = residual_.get() + j * size_;
      double sum = 0.0;
      for (std::size_t at = 0; at < in_contact; ++at) sum += f[at] * h[at] + f[half + at] * h[half + at];
      gram_(s, j) = gram_(j, s) = sum;
    }
    // The weights a: the newest takes 1 − sum gamma, each older j takes gamma_j, gamma fitting the
    // newest residual by its differences to the older ones, d_j = f_s − f_j.
    std::array<double, kSlots> a{};
    a[s] = 1.0;
    const int m = used_ - 1;
    if (m > 0) {
      std::array<int, kSlots> older{};
      for (int j = 0, i = 0; j < used_; ++j)
        if (j != s) older[i++] = j;
      Eigen::MatrixXd d(m, m);
      Eigen::VectorXd right(m);
      for (int i = 0; i < m; ++i) {
        const int u = older[i];
        right[i] = gram_(s, s) - gram_(s, u);
        for (int k = 0; k <= i; ++k) {
          const int v = older[k];
          d(i, k) = d(k, i) = gram_(s, s) - gram_(s, u) - gram_(s, v) + gram_(u, v);
        }
      }
      const Eigen::VectorXd gamma = d.ldlt().solve(right);
      if (gamma.allFinite()) {  // else the damped step alone
        for (int i = 0; i < m; ++i) {
          a[older[i]] = gamma[i];
          a[s] -= gamma[i];
        }
      }
    }
    const double* first = mixed_.get();
    for (std::size_t at = 0; at < size_; ++at) e[at] = a[0] * first[at];
    for (int j = 1; j < used_; ++j) {
      const double* h = mixed_.get() + j * size_;
      const double weight = a[j];
      for (std::size_t at = 0; at < size_; ++at) e[at] += weight * h[at];
    }
  }

 private:
  static constexpr int kSlots = kHistory + 1;
  std::size_t size_;
  std::unique_ptr<double[]> mixed_, residual_;  // e_i + r f_i and f_i, kSlots rings of size_
  Eigen::Matrix<double, kSlots, kSlots, Eigen::DontAlign> gram_;
  int newest_ = -1, used_ = 0;
};

// Element centres of a patch, in the order of its elements (ContactPatch::x1, x2 without the
// division by the mesh's row length per element: the loops below run 8 times per solve).
struct Centres {
  std::vector<double> x1_m, x2_m;
  explicit Centres(const ContactPatch& patch) : x1_m(patch.elements().count()), x2_m(patch.elements().count()) {
    for (std::size_t e = 0; e < x1_m.size(); ++e) {
      x1_m[e] = patch.x1(e);
      x2_m[e] = patch.x2(e);
    }
  }
};

// p = −mu p3 s/|s| per element (0 where s = 0); returns F1, F2 (N) and M3 about the origin (N m).
TangentialForces coulomb(const ContactPatch& patch, const Centres& centres, const std::vector<double>& s1,
                         const std::vector<double>& s2, double mu, std::vector<double>& p1, std::vector<double>& p2) {
  const double* p3 = patch.pressure_Pa().data();
  const double *x1 = centres.x1_m.data(), *x2 = centres.x2_m.data();
  const double *a = s1.data(), *b = s2.data();
  double *q1 = p1.data(), *q2 = p2.data();
  const std::size_t n = patch.pressure_Pa().size();
  double F1 = 0.0, F2 = 0.0, M3 = 0.0;
  for (std::size_t e = 0; e < n; ++e) {
    const double size = std::sqrt(a[e] * a[e] + b[e] * b[e]);  // slips of order 1e-3: no overflow
    const double scale = size > 0.0 ? -mu * p3[e] / size : 0.0;
    q1[e] = scale * a[e];
    q2[e] = scale * b[e];
    F1 += q1[e];
    F2 += q2[e];
    M3 += x1[e] * q2[e] - x2[e] * q1[e];
  }
  const double area = patch.mesh().element_area_m2();
  TangentialForces f;
  f.F1_N = F1 * area;
  f.F2_N = F2 * area;
  f.M3_Nm = M3 * area;
  return f;
}

// The rigid slip of one creepage: w = (xi − phi x2, eta + phi x1) (docs/METHOD.md §6).
struct OneCreepage {
  Creepage c;
  [[nodiscard]] std::pair<double, double> at(double x1, double x2) const {
    return {c.xi - c.phi * x2, c.eta + c.phi * x1};
  }
};

// The rigid slip of strip creepages: w = (xi_j, eta_j + phi_j x1), linear in x2 between strips.
struct Strips {
  const StripCreepages& strips;
  double x2_first_m, dx2_m;
  [[nodiscard]] std::pair<double, double> at(double x1, double x2) const {
    const double last = static_cast<double>(strips.size()) - 1.0;
    const double at = std::clamp((x2 - x2_first_m) / dx2_m, 0.0, last);
    const auto below = std::min(static_cast<std::size_t>(at), strips.size() > 1 ? strips.size() - 2 : std::size_t{0});
    const double t = strips.size() > 1 ? at - static_cast<double>(below) : 0.0;
    const Creepage& a = strips[below];
    const Creepage& b = strips[std::min(below + 1, strips.size() - 1)];
    const double xi = a.xi + t * (b.xi - a.xi), eta = a.eta + t * (b.eta - a.eta), phi = a.phi + t * (b.phi - a.phi);
    return {xi, eta + phi * x1};
  }
};

}  // namespace

// Where a marched patch's element takes the elastic slip from: bilinear between the four coarse
// grid elements around its centre (clamped to the grid), their grid indices and weights.
struct Bilinear {
  std::array<std::uint32_t, 4> at;
  std::array<double, 4> weight;
};

struct FullSlip::Coarse {
  ContactPatch patch;
  InfluenceOperator kernels;  // R on the coarse mesh (alpha = 0); each solve takes its own buffers
  Centres centres;            // of the coarse patch's elements
  Centres fine_centres;       // of the marched patch's elements
  // The coarse grid positions the iteration keeps its elastic slip at: the elements in contact (in
  // their order), then the others the stencils below reach.
  std::vector<std::size_t> kept;
  std::vector<Bilinear> fine_from_coarse;  // into `kept`
};

FullSlip::FullSlip(const ContactPatch& patch) : patch_(patch) {}
FullSlip::~FullSlip() = default;

const FullSlip::Coarse& FullSlip::coarse() const {
  std::call_once(made_, [this] {
    const int factor = automatic_coarsening(patch_.elements().count());
    ContactPatch copy = factor > 1 ? coarsened(patch_, factor) : patch_;
    InfluenceOperator R = make_steady_rolling_operator(copy.mesh(), copy.material(), 0.0);
    Centres centres(copy), fine(patch_);
    const Mesh& cm = copy.mesh();
    // Each grid position's place in `kept` (the elements in contact first).
    std::vector<std::size_t> kept = copy.elements().indices();
    std::vector<std::uint32_t> place(cm.size(), UINT32_MAX);
    for (std::size_t i = 0; i < kept.size(); ++i) place[kept[i]] = static_cast<std::uint32_t>(i);
    std::vector<Bilinear> stencils(fine.x1_m.size());
    for (std::size_t e = 0; e < stencils.size(); ++e) {
      const double a1 = std::clamp((fine.x1_m[e] - cm.x1_first_m) / cm.dx1_m, 0.0, cm.n1 - 1.0);
      const double a2 = std::clamp((fine.x2_m[e] - cm.x2_first_m) / cm.dx2_m, 0.0, cm.n2 - 1.0);
      const int i1 = static_cast<int>(a1), i2 = static_cast<int>(a2);
      const double t1 = a1 - i1, t2 = a2 - i2;
      const auto at = [&](int j1, int j2) {
        const std::size_t g = cm.index(std::min(j1, cm.n1 - 1), std::min(j2, cm.n2 - 1));
        if (place[g] == UINT32_MAX) {
          place[g] = static_cast<std::uint32_t>(kept.size());
          kept.push_back(g);
        }
        return place[g];
      };
      stencils[e] = {{at(i1, i2), at(i1 + 1, i2), at(i1, i2 + 1), at(i1 + 1, i2 + 1)},
                     {(1 - t1) * (1 - t2), t1 * (1 - t2), (1 - t1) * t2, t1 * t2}};
    }
    coarse_ = std::make_unique<Coarse>(Coarse{std::move(copy), std::move(R), std::move(centres), std::move(fine),
                                              std::move(kept), std::move(stencils)});
  });
  return *coarse_;
}

template <typename RigidSlip>
FullSlipTractions FullSlip::solve_with(const RigidSlip& rigid_slip, double mu, double adhesion_fraction) const {
  FullSlipTractions out;
  const double gate = smoothstep((kAdhesionFractionFrom - adhesion_fraction) / 0.1);
  if (gate <= 0.0) return out;
  const Coarse& c = coarse();
  const ContactPatch& cp = c.patch;
  const Mesh& cm = cp.mesh();
  const std::size_t n = cp.elements().count();
  const std::vector<std::size_t>& index = cp.elements().indices();
  InfluenceOperator R(cm, c.kernels);

  std::vector<double> w1(n), w2(n), s1(n), s2(n), p1(n), p2(n);
  double w_squares = 0.0;
  for (std::size_t e = 0; e < n; ++e) {
    std::tie(w1[e], w2[e]) = rigid_slip.at(c.centres.x1_m[e], c.centres.x2_m[e]);
    w_squares += w1[e] * w1[e] + w2[e] * w2[e];
  }
  const double w_rms = std::sqrt(w_squares / static_cast<double>(n));
  // No rigid slip, or one beyond any physical creepage (whose squares the iteration takes): the
  // march's result stands.
  if (!(w_rms > 0.0) || !(w_rms < 1e100)) return out;
  const double mu_F3 = mu * cp.normal_force_N();

  TangentialForces before = coulomb(cp, c.centres, w1, w2, mu, p1, p2);  // p_0: along the rigid slip
  const std::size_t half = c.kept.size(), size = 2 * half;  // the elastic slip at `kept`, by component
  std::vector<double> grid(2 * cm.size(), 0.0), product(2 * cm.size()), gathered(size), elastic(size);
  Anderson mixing(size);
  std::array<double, kSettledSteps> changes{};  // the last steps' force changes, step k's at k % kSettledSteps
  for (int k = 1; k <= kProducts; ++k) {
    out.products = k;
    for (std::size_t e = 0; e < n; ++e) {
      grid[index[e]] = p1[e];
      grid[cm.size() + index[e]] = p2[e];
    }
    R.apply_on_grid(grid, product);
    for (std::size_t i = 0; i < half; ++i) {
      gathered[i] = product[c.kept[i]];
      gathered[half + i] = product[cm.size() + c.kept[i]];
    }
    if (k == 1)
      elastic = gathered;
    else
      mixing.step(elastic, gathered, n);
    for (std::size_t e = 0; e < n; ++e) {  // the elements in contact lead `kept`
      s1[e] = w1[e] - elastic[e];
      s2[e] = w2[e] - elastic[half + e];
    }
    const TangentialForces now = coulomb(cp, c.centres, s1, s2, mu, p1, p2);
    const double change = std::hypot(now.F1_N - before.F1_N, now.F2_N - before.F2_N) / mu_F3;
    changes[static_cast<std::size_t>(k % kSettledSteps)] = change;
    before = now;
    const double previous = changes[static_cast<std::size_t>((k - 1) % kSettledSteps)];
    if (k > kSettledSteps && change < kConverged && previous < kConverged &&
        *std::max_element(changes.begin(), changes.end()) < kChangeTo)
      break;  // settled (k >= 4: three changes after the first product's)
  }
  const double force_change = *std::max_element(changes.begin(), changes.end());
  const bool finite = std::all_of(changes.begin(), changes.end(), [](double value) { return std::isfinite(value); });
  out.weight = gate * smoothstep((kChangeFrom - force_change) / (kChangeFrom - kChangeTo));
  if (!(out.weight > 0.0) || !finite) {
    out.weight = 0.0;
    return out;
  }

  // The elastic slip onto the marched patch's elements (bilinear between coarse element centres;
  // R p is defined on the whole coarse grid, in contact or not).
  const std::size_t fine = patch_.elements().count();
  std::vector<double> f1(fine), f2(fine);
  const double *e1 = elastic.data(), *e2 = elastic.data() + half;
  for (std::size_t e = 0; e < fine; ++e) {
    const Bilinear& b = c.fine_from_coarse[e];
    const double x1 = c.fine_centres.x1_m[e], x2 = c.fine_centres.x2_m[e];
    const double elastic1 = b.weight[0] * e1[b.at[0]] + b.weight[1] * e1[b.at[1]] + b.weight[2] * e1[b.at[2]] +
                            b.weight[3] * e1[b.at[3]];
    const double elastic2 = b.weight[0] * e2[b.at[0]] + b.weight[1] * e2[b.at[1]] + b.weight[2] * e2[b.at[2]] +
                            b.weight[3] * e2[b.at[3]];
    const auto [w1e, w2e] = rigid_slip.at(x1, x2);
    f1[e] = w1e - elastic1;
    f2[e] = w2e - elastic2;
  }
  out.p1_Pa.resize(fine);
  out.p2_Pa.resize(fine);
  out.forces = coulomb(patch_, c.fine_centres, f1, f2, mu, out.p1_Pa, out.p2_Pa);
  return out;
}

FullSlipTractions FullSlip::solve(const Creepage& creepage, double mu, double adhesion_fraction) const {
  return solve_with(OneCreepage{creepage}, mu, adhesion_fraction);
}

FullSlipTractions FullSlip::solve(const StripCreepages& creepages, double mu, double adhesion_fraction) const {
  return solve_with(Strips{creepages, patch_.mesh().x2_first_m, patch_.mesh().dx2_m}, mu, adhesion_fraction);
}

}  // namespace railcontact::detail
