#pragma once
// Stage: tangential problem, the one seam of its models. A TangentialModel is prepared on a
// contact patch with its options and then solves creepages to forces (and, on request, the
// tractions): nH-FastSim (per lobe on a patch of several, the equivalent ellipse's flexibilities on
// a patch too small for K2, or flexibilities given by a table), classic FastSim (Eq 9), and the
// exact and regularised solvers (Appendix, Eq A1). The wheelset, the case runner, the C API and
// Python choose a model by its TangentialSolver and go through this class only
// (docs/ARCHITECTURE.md "Adding a tangential model").
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "railcontact/contact_patch.hpp"
#include "railcontact/kalker.hpp"
#include "railcontact/tangential.hpp"

namespace railcontact {

struct TangentialModelOptions {
  TangentialSolver solver = TangentialSolver::nh_fastsim;
  // nh-fastsim: its recipe (the traction bound also for its small-patch fallback).
  NhFastSimOptions nh_fastsim{};
  // nh-fastsim on a patch of several connected lobes (NhFastSimPerLobe::has_several_lobes): each lobe
  // with its own flexibilities (NhFastSimPerLobe); false: one set of flexibilities for the patch.
  bool per_lobe = true;
  // nh-fastsim with these flexibilities (a flexibility table's) instead of K2's: no adhesion solve,
  // and per_lobe does not apply.
  std::optional<NhFastSimFlexibilities> given_flexibilities;
  // The ellipse of Eq 9 (semi-axes a along X1 and b, m) for fastsim and for nh-fastsim's fallback on
  // a patch too small for K2 (fewer than 20 elements in contact, docs/WHEELSET.md §5); unset: the
  // patch's equivalent ellipse (equivalent_ellipse_semi_axes).
  std::optional<std::array<double, 2>> ellipse_semi_axes_m;
  // exact, exact-regularised.
  RollingOptions rolling{};
};

// Throws Error (invalid_input) naming the field, its value and the range unless the solver is one of
// TangentialSolver's and the options of the chosen model lie in their ranges (NhFastSimOptions,
// RollingOptions, positive finite given flexibilities and semi-axes).
void validate(const TangentialModelOptions& options);

// The semi-axes (a along X1, b; m) of a patch's equivalent ellipse, the ellipse of Eq 9 for classic
// FastSim on a non-elliptical patch: the axis ratio of the box around its elements in contact, their
// area kept (Piotrowski & Kik 2008). Throws Error (invalid_input) for a patch without elements in
// contact.
std::array<double, 2> equivalent_ellipse_semi_axes(const ContactPatch& patch);

// What a solve returns.
enum class TangentialOutput {
  forces,  // forces, spin moment and adhesion fraction (FastSim marches without per-element output)
  // forces and spin moment only, the adhesion fraction left 0: FastSim's cheapest march (a table
  // lookup's); the exact solvers give their adhesion fraction all the same
  forces_only,
  fields,  // also the tractions and slip flags per contact element
  // forces and, from strip creepages, each strip's sums of traction (what a conformal patch turns
  // strip by strip into its own frame): strip_F1_N, strip_F2_N
  strip_forces,
};

// The table-driven model's patch (WheelsetTable, docs/WHEELSET_TABLE.md): nH-FastSim as a table
// stores a patch, each lobe a coarse copy with the flexibilities solved when the table was built,
// so that a lookup solves no adhesion problem. As NhFastSimPerLobe: each lobe takes the creepages at
// its own centre; forces summed, the spin moment about the patch's origin; blended with the whole
// patch's where a neck widens.
struct StoredLobe {
  ContactPatch patch;  // the lobe's coarse copy (its origin its centre of pressure)
  Flexibility flexibility;
  double x1_centre_m = 0.0, x2_centre_m = 0.0;  // its centre of pressure in the patch's coordinates
  CreepageCoupling coupling;  // nH-FastSim's creepage coupling about the copy's origin (tangential.hpp)
};
struct StoredPatch {
  std::vector<StoredLobe> lobes;  // one for a patch of one lobe (its centre the patch's origin)
  // Where a neck widens (NhFastSimPerLobe::whole_patch_weight): the whole patch, blended with the
  // lobes' sum with this weight.
  std::optional<StoredLobe> whole;
  double whole_patch_weight = 0.0;
};

struct TangentialSolution {
  TangentialForces forces;  // on the wheel, Kalker's sign convention; M3 about the patch's origin
  double adhesion_fraction = 0.0;  // elements in adhesion / elements in contact
  // TangentialOutput::fields (the exact solvers give them always): per contact element, in the
  // order of patch.elements().indices().
  std::vector<double> p1_Pa, p2_Pa;
  std::vector<std::uint8_t> slip;  // 1 where the element slips
  int newton_iterations = 0;       // exact solvers
  int krylov_iterations = 0;       // exact solvers: all inner GMRES iterations
  // TangentialOutput::strip_forces from strip creepages: per column of the patch's mesh, the
  // tractions of its elements in contact times their area (N), along X1 and along the strip.
  std::vector<double> strip_F1_N, strip_F2_N;
};

namespace detail {
class TangentialModelImpl;  // one implementation per model (src/tangential/tangential_model.cpp)
}  // namespace detail

// A tangential model prepared on one contact patch. Immutable after construction; copies share the
// prepared data; solves are thread-safe.
class TangentialModel {
 public:
  // Prepares options.solver on the patch: nh-fastsim solves K2 on the (coarsened) patch or each lobe
  // (Eq 18-20) unless flexibilities are given; fastsim takes Eq 9's flexibilities of the ellipse; the
  // exact solvers keep the patch. Throws Error (invalid_input) for bad options (validate) or a patch
  // without elements in contact, and what NhFastSim throws (not_converged).
  TangentialModel(const ContactPatch& patch, const TangentialModelOptions& options);
  // The table-driven model: nH-FastSim (options.solver must be it; its bound applies) on a stored
  // patch with its stored flexibilities. It gives forces for the creepages at the patch's origin;
  // fields and strip creepages only on a patch of one lobe (the lobe's copy is then the patch).
  // Throws Error (invalid_input) for another solver, bad options, no lobe, a lobe without elements in
  // contact or flexibilities that are not positive and finite.
  TangentialModel(const StoredPatch& patch, const TangentialModelOptions& options);

  // Forces (and fields on request) for the creepages at the patch's origin. Throws Error
  // (invalid_input) unless mu > 0 and the creepages are finite; the exact solvers' not_converged.
  [[nodiscard]] TangentialSolution solve(const Creepage& creepage, double mu,
                                         TangentialOutput output = TangentialOutput::fields) const;
  // The same from each strip's creepages (one per column of the patch's mesh: a conformal patch,
  // docs/WHEELSET.md §4). Throws as above, and for another count of strips.
  [[nodiscard]] TangentialSolution solve(const StripCreepages& creepages, double mu,
                                         TangentialOutput output = TangentialOutput::fields) const;

  [[nodiscard]] TangentialSolver solver() const;
  // FastSim's flexibilities L1-L3 (m/Pa): nh-fastsim's from K2 (per lobe: the most loaded lobe's),
  // given, or Eq 9's fallback; fastsim's of Eq 9. Empty for the exact solvers.
  [[nodiscard]] std::optional<Flexibility> flexibility() const;
  // nh-fastsim's creepage coupling (CreepageCoupling, railcontact/tangential.hpp; per lobe: the most
  // loaded lobe's); zero for the other solvers and for given flexibilities.
  [[nodiscard]] CreepageCoupling coupling() const;
  // Where the flexibilities come from, in words ("K2", "K2 of the patch coarsened by 2", "K2 of each
  // of its 2 lobes (the most loaded one's shown)", "given", "Eq 9"); empty for the exact solvers.
  [[nodiscard]] const std::string& flexibility_source() const;
  // GMRES iterations of the preparation (nh-fastsim's K2 solves, every lobe's); 0 without.
  [[nodiscard]] int preparation_krylov_iterations() const;
  // nh-fastsim on one lobe (K2 on the fly or given flexibilities): its NhFastSim, with K2 and the
  // normalisation of Eq 22-23; nullptr otherwise.
  [[nodiscard]] const NhFastSim* nh_fastsim() const;
  // nh-fastsim per lobe: its NhFastSimPerLobe; nullptr otherwise.
  [[nodiscard]] const NhFastSimPerLobe* nh_fastsim_per_lobe() const;

 private:
  std::shared_ptr<const detail::TangentialModelImpl> impl_;
};

}  // namespace railcontact
