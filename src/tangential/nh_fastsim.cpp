// nH-FastSim's recipe, in one place (docs/METHOD.md §7, docs/FASTSIM.md): the coarse patch for the
// adhesion solve, the force rows of K2 (Eq 18), the term-by-term flexibilities (Eq 19-20), the
// traction bound, and FastSim's march (Eq 2-8). Every user of the method — case runs, the
// flexibility table, the studies, the benchmarks — builds it here.
#include <cmath>
#include <optional>
#include <utility>

#include <fmt/format.h>

#include "railcontact/error.hpp"
#include "railcontact/tangential.hpp"
#include "tangential/adhesion_tuning.hpp"
#include "tangential/cropped_patch.hpp"

namespace railcontact {
namespace {

// K2 for the flexibilities: the two force rows by adjoint solves when the term-by-term match
// needs no more (2 solves instead of 3), to GMRES tolerance 3e-3: the entries the match uses (C11,
// C22, C23) to within 2.9e-3 relative of a 1e-9 solve on 72 coarse S1002/UIC60 patches and 15
// ellipses (6.5e-4 and 7.6e-4 at 1e-3; build/bench/k2_tolerance), far below K2's discretisation error (~1 %) and the change
// from coarsening the patch (1-3 %), with 13 % fewer GMRES iterations than 1e-3 (13.1 against 15.0
// per patch) and 65 % fewer than 1e-9 (docs/FASTSIM.md "K2's solves").
AdhesionOptions adhesion_options(const NhFastSimOptions& options) {
  AdhesionOptions adhesion;
  adhesion.collocation_offset = options.collocation_offset;
  adhesion.part = options.match == FlexibilityMatch::term_by_term ? CreepageMatrixPart::force_rows
                                                                   : CreepageMatrixPart::full;
  adhesion.tolerance = 3e-3;
  return adhesion;
}

// The adjoint solves on coarse S1002/UIC60 patches (130-800 elements) converge fastest with a
// smaller shift than ellipses' tight solves want: 14.3 GMRES iterations for both rows at
// gamma = 1.5 against 15.6 at 3 (mean over 30 patches); ellipses of 150-600 elements need at most
// 6 % more iterations than at 3 (docs/FASTSIM.md).
constexpr AdhesionTuning kAdhesionTuning{AdhesionPreconditioner::marching_half_laplacian, 1.5};

void validate(const NhFastSimOptions& options) {
  require(options.flexibility_coarsening >= 0 && options.flexibility_coarsening <= kMaximumCoarsening, [&] {
    return fmt::format("nH-FastSim: the flexibility coarsening {} must lie in [0, {}] (0: automatic)",
                       options.flexibility_coarsening, kMaximumCoarsening);
  });
}

}  // namespace

namespace detail {

int automatic_coarsening(std::size_t elements_in_contact) {
  constexpr double kMinimumCoarseElements = 250;
  constexpr std::size_t kCoarsenFrom = 400;
  const auto n = static_cast<double>(elements_in_contact);
  int factor = 1;
  while (factor < kMaximumCoarsening && n / ((factor + 1) * (factor + 1)) >= kMinimumCoarseElements) ++factor;
  if (factor == 1 && elements_in_contact >= kCoarsenFrom) factor = 2;
  return factor;
}

CoarseBlocks automatic_coarse_blocks(std::size_t elements_in_contact) {
  const int factor = automatic_coarsening(elements_in_contact);
  return {factor, factor >= 3 ? factor + 1 : factor};
}

}  // namespace detail

int NhFastSim::automatic_coarsening(const ContactPatch& patch) {
  return detail::automatic_coarsening(patch.elements().count());
}

CoarseBlocks NhFastSim::automatic_coarse_blocks(const ContactPatch& patch) {
  return detail::automatic_coarse_blocks(patch.elements().count());
}

NhFastSim::NhFastSim(FastSim fastsim, NhFastSimFlexibilities flexibilities, std::optional<Matrix3> K2,
                     CoarseBlocks coarse_blocks, int krylov_iterations)
    : fastsim_(std::move(fastsim)),
      flexibilities_(flexibilities),
      creepage_matrix_(std::move(K2)),
      coarse_blocks_(coarse_blocks),
      krylov_iterations_(krylov_iterations) {}

NhFastSim::NhFastSim(const ContactPatch& patch, const NhFastSimOptions& options)
    : NhFastSim(FastSim(patch, options.bound), {}, std::nullopt, {0, 0}, 0) {
  validate(options);
  coarse_blocks_ = options.flexibility_coarsening > 0
                       ? CoarseBlocks{options.flexibility_coarsening, options.flexibility_coarsening}
                       : automatic_coarse_blocks(patch);
  // Steps 1-3: K2 and FastSim's full-adhesion forces (S D B, which does not depend on the bound)
  // on the same, possibly coarsened, patch.
  const bool coarse_patch = coarse_blocks_ != CoarseBlocks{1, 1};
  const ContactPatch coarse = coarse_patch ? coarsened(patch, coarse_blocks_) : ContactPatch{};
  const ContactPatch& flexibility_patch = coarse_patch ? coarse : patch;
  const AdhesionSolution K2 = solve_full_adhesion(flexibility_patch.elements(), flexibility_patch.material(),
                                                  adhesion_options(options), kAdhesionTuning);
  const Matrix3& k = K2.creepage_matrix;
  // FastSim on the patch K2 was solved on: its S D B (Eq 19) for the match and the coupling.
  const std::optional<FastSim> coarse_fastsim = coarse_patch ? std::optional<FastSim>(FastSim(coarse)) : std::nullopt;
  const FastSim& matched = coarse_patch ? *coarse_fastsim : fastsim_;
  flexibilities_.flexibility = nh_fastsim_flexibility(matched, k, options.match);
  flexibilities_.f11_N = -k(0, 0);
  flexibilities_.f22_N = -k(1, 1);
  flexibilities_.f23_Nm = -k(1, 2);
  if (options.creepage_coupling) flexibilities_.coupling = creepage_coupling(matched, k, flexibilities_.flexibility);
  creepage_matrix_ = k;
  krylov_iterations_ = K2.iterations;
}

NhFastSim::NhFastSim(const ContactPatch& patch, const NhFastSimFlexibilities& given, const NhFastSimOptions& options)
    : NhFastSim(FastSim(patch, options.bound), given, std::nullopt, {0, 0}, 0) {
  const Flexibility& L = given.flexibility;
  require(std::isfinite(L.L1) && std::isfinite(L.L2) && std::isfinite(L.L3) && L.L1 > 0 && L.L2 > 0 && L.L3 > 0, [&] {
    return fmt::format("nH-FastSim: the given flexibilities L1 = {:g}, L2 = {:g}, L3 = {:g} m/Pa must be positive and "
                       "finite",
                       L.L1, L.L2, L.L3);
  });
}

TangentialForces NhFastSim::forces(const Creepage& creepage, double mu) const {
  return fastsim_.forces(creepage, flexibilities_.flexibility, mu, flexibilities_.coupling);
}

FastSimResult NhFastSim::solve(const Creepage& creepage, double mu) const {
  return fastsim_.solve(creepage, flexibilities_.flexibility, mu, flexibilities_.coupling);
}

FastSimResult NhFastSim::solve(const StripCreepages& creepages, double mu) const {
  return fastsim_.solve(creepages, flexibilities_.flexibility, mu, flexibilities_.coupling);
}

FastSimResult NhFastSim::forces_and_adhesion(const Creepage& creepage, double mu) const {
  return fastsim_.forces_and_adhesion(creepage, flexibilities_.flexibility, mu, flexibilities_.coupling);
}

Creepage NhFastSim::creepage_from_normalised(double xi_normalised, double eta_normalised, double phi_per_m, double mu,
                                             double normal_force_N) const {
  const double saturation = 3.0 * mu * normal_force_N;  // Eq 22-23
  return {xi_normalised * saturation / flexibilities_.f11_N, eta_normalised * saturation / flexibilities_.f22_N,
          phi_per_m};
}

}  // namespace railcontact
