// The tangential models behind one seam (include/railcontact/tangential_model.hpp): which model a
// TangentialSolver names, what each prepares on a patch, and how each solves. A new model is a new
// TangentialSolver (with its name in tangential_solver.cpp), an implementation here and its case in
// make_model(); the front ends translate its name (docs/ARCHITECTURE.md "Adding a tangential model").
#include "railcontact/tangential_model.hpp"

#include <fmt/core.h>

#include <cmath>
#include <utility>

#include "railcontact/error.hpp"
#include "tangential/cropped_patch.hpp"
#include "tangential/lobe_sum.hpp"

namespace railcontact {

namespace detail {

class TangentialModelImpl {
 public:
  TangentialModelImpl() = default;
  TangentialModelImpl(const TangentialModelImpl&) = delete;
  TangentialModelImpl& operator=(const TangentialModelImpl&) = delete;
  virtual ~TangentialModelImpl() = default;
  [[nodiscard]] virtual TangentialSolution solve(const Creepage& creepage, double mu, TangentialOutput output) const = 0;
  [[nodiscard]] virtual TangentialSolution solve(const StripCreepages& creepages, double mu,
                                                 TangentialOutput output) const = 0;

  TangentialSolver solver = TangentialSolver::nh_fastsim;
  // The column of the patch's mesh of each element in contact (TangentialOutput::strip_forces from
  // the fields), and the count of columns.
  std::vector<std::uint32_t> element_column;
  std::size_t columns = 0;
  double element_area_m2 = 0.0;
  std::optional<Flexibility> flexibility;
  CreepageCoupling coupling;
  std::string flexibility_source;
  int preparation_krylov_iterations = 0;
  const NhFastSim* nh_fastsim = nullptr;
  const NhFastSimPerLobe* per_lobe = nullptr;
};

}  // namespace detail

namespace {

using detail::TangentialModelImpl;

// Whether the output asks for nothing beyond the forces (and the adhesion fraction).
bool forces_alone(TangentialOutput output) {
  return output == TangentialOutput::forces || output == TangentialOutput::forces_only;
}

TangentialSolution only_forces(const TangentialForces& forces) {
  TangentialSolution s;
  s.forces = forces;
  return s;
}

TangentialSolution from_fastsim(FastSimResult r, TangentialOutput output) {
  TangentialSolution s;
  s.forces = r.forces;
  s.adhesion_fraction = r.adhesion_fraction;
  if (!forces_alone(output)) {
    s.p1_Pa = std::move(r.p1_Pa);
    s.p2_Pa = std::move(r.p2_Pa);
    s.slip = std::move(r.slip);
  }
  return s;
}

TangentialSolution from_rolling(RollingSolution r) {
  TangentialSolution s;
  s.forces = r.forces;
  s.adhesion_fraction = r.adhesion_fraction;
  s.p1_Pa = std::move(r.p1_Pa);
  s.p2_Pa = std::move(r.p2_Pa);
  s.slip = std::move(r.slip);
  s.newton_iterations = r.newton_iterations;
  s.krylov_iterations = r.krylov_iterations;
  return s;
}

TangentialSolution from_strip_forces(StripForces f) {
  TangentialSolution s;
  s.forces = f.forces;
  s.adhesion_fraction = f.adhesion_fraction;
  s.strip_F1_N = std::move(f.F1_N);
  s.strip_F2_N = std::move(f.F2_N);
  return s;
}

// FastSim with fixed flexibilities: classic FastSim (Eq 9, the parabolic bound of Eq 1) and
// nH-FastSim's fallback on a patch too small for K2 (Eq 9 with nH-FastSim's bound).
class FastSimModel final : public TangentialModelImpl {
 public:
  FastSimModel(FastSim fastsim, Flexibility L) : fastsim_(std::move(fastsim)), L_(L) { flexibility = L; }
  TangentialSolution solve(const Creepage& c, double mu, TangentialOutput output) const override {
    if (output == TangentialOutput::forces_only) return only_forces(fastsim_.forces(c, L_, mu));
    return from_fastsim(output == TangentialOutput::forces ? fastsim_.forces_and_adhesion(c, L_, mu)
                                                           : fastsim_.solve(c, L_, mu),
                        output);
  }
  TangentialSolution solve(const StripCreepages& c, double mu, TangentialOutput output) const override {
    if (output == TangentialOutput::strip_forces) return from_strip_forces(fastsim_.strip_forces(c, L_, mu));
    return from_fastsim(fastsim_.solve(c, L_, mu), output);
  }

 private:
  FastSim fastsim_;
  Flexibility L_;
};

// nH-FastSim on one patch (Eq 1-8 with Eq 19-20's flexibilities, from K2 or given).
class NhFastSimModel final : public TangentialModelImpl {
 public:
  explicit NhFastSimModel(NhFastSim nh) : nh_(std::move(nh)) {
    nh_fastsim = &nh_;
    flexibility = nh_.flexibility();
    coupling = nh_.coupling();
  }
  TangentialSolution solve(const Creepage& c, double mu, TangentialOutput output) const override {
    if (output == TangentialOutput::forces_only) return only_forces(nh_.forces(c, mu));
    return from_fastsim(output == TangentialOutput::forces ? nh_.forces_and_adhesion(c, mu) : nh_.solve(c, mu),
                        output);
  }
  TangentialSolution solve(const StripCreepages& c, double mu, TangentialOutput output) const override {
    return from_fastsim(nh_.solve(c, mu), output);
  }

 private:
  NhFastSim nh_;
};

// nH-FastSim per lobe (NhFastSimPerLobe, docs/WHEELSET.md §8).
class NhFastSimPerLobeModel final : public TangentialModelImpl {
 public:
  explicit NhFastSimPerLobeModel(NhFastSimPerLobe lobes) : lobes_(std::move(lobes)) {
    per_lobe = &lobes_;
    flexibility = lobes_.flexibility();  // the most loaded lobe's
    coupling = lobes_.coupling();
  }
  TangentialSolution solve(const Creepage& c, double mu, TangentialOutput output) const override {
    return from_fastsim(lobes_.solve(c, mu), output);
  }
  TangentialSolution solve(const StripCreepages& c, double mu, TangentialOutput output) const override {
    return from_fastsim(lobes_.solve(c, mu), output);
  }

 private:
  NhFastSimPerLobe lobes_;
};

// The exact solver (Coulomb's law) or the regularised one (Eq A1) on the patch itself.
class RollingModel final : public TangentialModelImpl {
 public:
  RollingModel(const ContactPatch& patch, const RollingOptions& options, bool regularised)
      : patch_(patch), options_(options), regularised_(regularised) {}
  TangentialSolution solve(const Creepage& c, double mu, TangentialOutput) const override {
    return from_rolling(regularised_ ? solve_rolling_regularised(patch_, c, mu, options_)
                                     : solve_rolling_exact(patch_, c, mu, options_));
  }
  TangentialSolution solve(const StripCreepages& c, double mu, TangentialOutput) const override {
    return from_rolling(regularised_ ? solve_rolling_regularised(patch_, c, mu, options_)
                                     : solve_rolling_exact(patch_, c, mu, options_));
  }

 private:
  ContactPatch patch_;
  RollingOptions options_;
  bool regularised_;
};

void require_positive(double value, const char* field, const char* unit) {
  require(std::isfinite(value) && value > 0.0, [&] {
    return fmt::format("tangential model: {} = {}{} must be positive and finite", field, value, unit);
  });
}

// The table-driven model (StoredPatch): FastSim on each stored lobe's copy with its stored
// flexibilities, summed and blended as NhFastSimPerLobe does (tangential/lobe_sum.hpp).
class StoredPatchModel final : public TangentialModelImpl {
 public:
  StoredPatchModel(const StoredPatch& patch, const TractionBound& bound) : whole_weight_(patch.whole_patch_weight) {
    for (const StoredLobe& lobe : patch.lobes) lobes_.push_back(prepared(lobe, bound));
    if (patch.whole && whole_weight_ > 0.0) whole_.push_back(prepared(*patch.whole, bound));
    flexibility = patch.lobes.front().flexibility;
    coupling = patch.lobes.front().coupling;
  }
  TangentialSolution solve(const Creepage& c, double mu, TangentialOutput output) const override {
    if (lobes_.size() == 1 && whole_.empty()) return one_lobe(lobes_.front(), c, mu, output);
    require(forces_alone(output),
            "tangential model: a stored patch of several lobes gives forces only (its lobes are separate copies)");
    TangentialSolution sum;
    double adhesion_elements = 0.0, elements = 0.0;
    for (const Lobe& lobe : lobes_) {
      const TangentialSolution s = one_lobe(lobe, c, mu, output);
      sum.forces.F1_N += s.forces.F1_N;
      sum.forces.F2_N += s.forces.F2_N;
      sum.forces.M3_Nm += s.forces.M3_Nm;
      const auto n = static_cast<double>(lobe.fastsim.element_count());
      adhesion_elements += s.adhesion_fraction * n;
      elements += n;
    }
    sum.adhesion_fraction = adhesion_elements / elements;
    if (whole_.empty()) return sum;
    const TangentialSolution whole = one_lobe(whole_.front(), c, mu, output);
    sum.forces = detail::blend(sum.forces, whole.forces, whole_weight_);
    sum.adhesion_fraction = detail::blend(sum.adhesion_fraction, whole.adhesion_fraction, whole_weight_);
    return sum;
  }
  TangentialSolution solve(const StripCreepages& c, double mu, TangentialOutput output) const override {
    require(lobes_.size() == 1 && whole_.empty(),
            "tangential model: a stored patch of several lobes takes the creepages at its origin, not per strip");
    const Lobe& lobe = lobes_.front();
    if (output == TangentialOutput::strip_forces)
      return from_strip_forces(lobe.fastsim.strip_forces(c, lobe.L, mu, lobe.coupling));
    return from_fastsim(lobe.fastsim.solve(c, lobe.L, mu, lobe.coupling), output);
  }

 private:
  struct Lobe {
    FastSim fastsim;
    Flexibility L;
    double x1_m, x2_m;  // its centre in the patch's coordinates
    CreepageCoupling coupling;
  };
  static Lobe prepared(const StoredLobe& lobe, const TractionBound& bound) {
    const Flexibility& L = lobe.flexibility;
    require_positive(L.L1, "a stored lobe's flexibility.L1", " m/Pa");
    require_positive(L.L2, "a stored lobe's flexibility.L2", " m/Pa");
    require_positive(L.L3, "a stored lobe's flexibility.L3", " m/Pa");
    require(std::isfinite(lobe.x1_centre_m) && std::isfinite(lobe.x2_centre_m),
            "tangential model: a stored lobe's centre must be finite");
    require(lobe.patch.elements().count() > 0, "tangential model: a stored lobe has no element in contact");
    require(lobe.coupling.plausible(),
            "tangential model: a stored lobe's creepage coupling must have its ratios within ±1 and its lengths "
            "within ±0.1 m");
    return {FastSim(lobe.patch, bound), L, lobe.x1_centre_m, lobe.x2_centre_m, lobe.coupling};
  }
  // One lobe's solution for the creepages at the patch's origin: at its centre, M3 moved back.
  static TangentialSolution one_lobe(const Lobe& lobe, const Creepage& c, double mu, TangentialOutput output) {
    const Creepage at = detail::creepage_at(c, lobe.x1_m, lobe.x2_m);
    TangentialSolution s;
    if (output == TangentialOutput::forces_only)
      s = only_forces(lobe.fastsim.forces(at, lobe.L, mu, lobe.coupling));
    else if (output == TangentialOutput::forces)
      s = from_fastsim(lobe.fastsim.forces_and_adhesion(at, lobe.L, mu, lobe.coupling), output);
    else
      s = from_fastsim(lobe.fastsim.solve(at, lobe.L, mu, lobe.coupling), output);
    s.forces.M3_Nm = detail::moment_about_origin_Nm(s.forces, lobe.x1_m, lobe.x2_m);
    return s;
  }
  std::vector<Lobe> lobes_, whole_;
  double whole_weight_;
};

std::string coarse_blocks_source(CoarseBlocks blocks) {
  if (blocks == CoarseBlocks{1, 1}) return "K2";
  if (blocks.along == blocks.across) return fmt::format("K2 of the patch coarsened by {}", blocks.along);
  return fmt::format("K2 of the patch coarsened in blocks of {} elements along x1 by {} across", blocks.along,
                     blocks.across);
}

// Eq 9's flexibilities of the options' ellipse, or of the patch's equivalent one.
Flexibility ellipse_flexibility(const ContactPatch& patch, const TangentialModelOptions& options) {
  const std::array<double, 2> ab =
      options.ellipse_semi_axes_m ? *options.ellipse_semi_axes_m : equivalent_ellipse_semi_axes(patch);
  return fastsim_flexibility(ab[0], ab[1], patch.material());
}

std::unique_ptr<TangentialModelImpl> make_nh_fastsim(const ContactPatch& patch, const TangentialModelOptions& options) {
  if (options.given_flexibilities) {
    auto model = std::make_unique<NhFastSimModel>(NhFastSim(patch, *options.given_flexibilities, options.nh_fastsim));
    model->flexibility_source = "given";
    return model;
  }
  if (options.per_lobe && NhFastSimPerLobe::has_several_lobes(patch)) {
    auto model = std::make_unique<NhFastSimPerLobeModel>(NhFastSimPerLobe(patch, options.nh_fastsim));
    model->flexibility_source =
        fmt::format("K2 of each of its {} lobes (the most loaded one's shown)", model->per_lobe->lobe_count());
    model->preparation_krylov_iterations = model->per_lobe->krylov_iterations();
    return model;
  }
  // A patch just appeared may have too few elements for K2 (docs/WHEELSET.md §5).
  std::optional<NhFastSim> nh = detail::nh_fastsim_unless_too_small(patch, options.nh_fastsim);
  if (!nh) {
    auto model = std::make_unique<FastSimModel>(FastSim(patch, options.nh_fastsim.bound),
                                                ellipse_flexibility(patch, options));
    model->flexibility_source = "Eq 9 (too few elements for K2)";
    return model;
  }
  auto model = std::make_unique<NhFastSimModel>(std::move(*nh));
  model->flexibility_source = coarse_blocks_source(model->nh_fastsim->coarse_blocks());
  model->preparation_krylov_iterations = model->nh_fastsim->krylov_iterations();
  return model;
}

std::unique_ptr<TangentialModelImpl> make_model(const ContactPatch& patch, const TangentialModelOptions& options) {
  std::unique_ptr<TangentialModelImpl> model;
  switch (options.solver) {
    case TangentialSolver::nh_fastsim: model = make_nh_fastsim(patch, options); break;
    case TangentialSolver::fastsim:
      model = std::make_unique<FastSimModel>(FastSim(patch, TractionBound::parabolic()),
                                             ellipse_flexibility(patch, options));
      model->flexibility_source = "Eq 9";
      break;
    case TangentialSolver::exact:
    case TangentialSolver::exact_regularised:
      require(patch.elements().count() > 0, "tangential model: the contact patch has no element in contact");
      model = std::make_unique<RollingModel>(patch, options.rolling,
                                             options.solver == TangentialSolver::exact_regularised);
      return model;
  }
  return model;
}


}  // namespace

std::array<double, 2> equivalent_ellipse_semi_axes(const ContactPatch& patch) {
  const std::vector<std::size_t>& elements = patch.elements().indices();
  require(!elements.empty(), "equivalent ellipse: the contact patch has no element in contact");
  const Mesh& mesh = patch.mesh();
  const detail::IndexBox box = detail::bounding_box(mesh, elements);
  const double extent1 = (box.hi1 - box.lo1 + 1) * mesh.dx1_m, extent2 = (box.hi2 - box.lo2 + 1) * mesh.dx2_m;
  const double area = static_cast<double>(elements.size()) * mesh.element_area_m2();
  const double scale = std::sqrt(area / (M_PI * 0.25 * extent1 * extent2));
  return {0.5 * extent1 * scale, 0.5 * extent2 * scale};
}

void validate(const TangentialModelOptions& options) {
  (void)tangential_solver_of(static_cast<int>(options.solver), "tangential model: solver", "a TangentialSolver");
  const NhFastSimOptions& nh = options.nh_fastsim;
  require(std::isfinite(nh.bound.skew) && nh.bound.skew >= 0.0 && nh.bound.skew <= 1.0, [&] {
    return fmt::format("tangential model: nh_fastsim.bound.skew = {} must lie in [0, 1]", nh.bound.skew);
  });
  require(nh.bound.slip_direction == SlipDirection::radial ||
              nh.bound.slip_direction == SlipDirection::flexibility_weighted ||
              nh.bound.slip_direction == SlipDirection::rigid_slip ||
              nh.bound.slip_direction == SlipDirection::elastic_slip,
          "tangential model: nh_fastsim.bound.slip_direction is not a SlipDirection");
  require(nh.match == FlexibilityMatch::term_by_term || nh.match == FlexibilityMatch::full_matrix ||
              nh.match == FlexibilityMatch::spin_from_moment,
          [&] {
            return fmt::format("tangential model: nh_fastsim.match = {} is not a FlexibilityMatch (0 term-by-term, 1 "
                               "full-matrix, 2 spin-from-moment)",
                               static_cast<int>(nh.match));
          });
  require(nh.flexibility_coarsening >= 0 && nh.flexibility_coarsening <= kMaximumCoarsening, [&] {
    return fmt::format("tangential model: nh_fastsim.flexibility_coarsening = {} must lie in [0, {}] (0: automatic)",
                       nh.flexibility_coarsening, kMaximumCoarsening);
  });
  require(std::isfinite(nh.collocation_offset) && nh.collocation_offset >= kMinimumCollocationOffset &&
              nh.collocation_offset <= 1.0,
          [&] {
            return fmt::format("tangential model: nh_fastsim.collocation_offset = {} must lie in [{}, 1]",
                               nh.collocation_offset, kMinimumCollocationOffset);
          });
  if (options.given_flexibilities) {
    const Flexibility& L = options.given_flexibilities->flexibility;
    require_positive(L.L1, "given_flexibilities.flexibility.L1", " m/Pa");
    require_positive(L.L2, "given_flexibilities.flexibility.L2", " m/Pa");
    require_positive(L.L3, "given_flexibilities.flexibility.L3", " m/Pa");
  }
  if (options.ellipse_semi_axes_m) {
    require_positive((*options.ellipse_semi_axes_m)[0], "ellipse_semi_axes_m[0]", " m");
    require_positive((*options.ellipse_semi_axes_m)[1], "ellipse_semi_axes_m[1]", " m");
  }
  validate(options.rolling);
}

TangentialModel::TangentialModel(const ContactPatch& patch, const TangentialModelOptions& options) {
  validate(options);
  std::unique_ptr<detail::TangentialModelImpl> model = make_model(patch, options);
  model->solver = options.solver;
  const std::vector<std::size_t>& indices = patch.elements().indices();
  const auto n1 = static_cast<std::size_t>(patch.mesh().n1);
  model->element_column.reserve(indices.size());
  for (std::size_t k : indices) model->element_column.push_back(static_cast<std::uint32_t>(k / n1));
  model->columns = static_cast<std::size_t>(patch.mesh().n2);
  model->element_area_m2 = patch.mesh().element_area_m2();
  impl_ = std::move(model);
}

TangentialModel::TangentialModel(const StoredPatch& patch, const TangentialModelOptions& options) {
  validate(options);
  require(options.solver == TangentialSolver::nh_fastsim, [&] {
    return fmt::format("tangential model: a stored patch is solved by nh-fastsim, not {}", solver_name(options.solver));
  });
  require(!patch.lobes.empty(), "tangential model: a stored patch needs at least one lobe");
  require(std::isfinite(patch.whole_patch_weight) && patch.whole_patch_weight >= 0.0 && patch.whole_patch_weight <= 1.0,
          [&] {
            return fmt::format("tangential model: a stored patch's whole_patch_weight = {} must lie in [0, 1]",
                               patch.whole_patch_weight);
          });
  require(patch.whole_patch_weight == 0.0 || patch.whole,
          "tangential model: a stored patch with a whole_patch_weight above 0 needs its whole patch");
  auto model = std::make_unique<StoredPatchModel>(patch, options.nh_fastsim.bound);
  model->solver = options.solver;
  model->flexibility_source = patch.lobes.size() == 1 ? "given" : fmt::format("given for each of its {} lobes", patch.lobes.size());
  if (patch.lobes.size() == 1 && patch.whole_patch_weight == 0.0) {
    const ContactPatch& one = patch.lobes.front().patch;
    const auto n1 = static_cast<std::size_t>(one.mesh().n1);
    for (std::size_t k : one.elements().indices()) model->element_column.push_back(static_cast<std::uint32_t>(k / n1));
    model->columns = static_cast<std::size_t>(one.mesh().n2);
    model->element_area_m2 = one.mesh().element_area_m2();
  }
  impl_ = std::move(model);
}

namespace {

// TangentialOutput::strip_forces from a model that gave the fields: each column's sums.
void strip_sums_from_fields(const detail::TangentialModelImpl& model, TangentialSolution& s) {
  if (!s.strip_F1_N.empty() || s.p1_Pa.size() != model.element_column.size()) return;
  s.strip_F1_N.assign(model.columns, 0.0);
  s.strip_F2_N.assign(model.columns, 0.0);
  for (std::size_t e = 0; e < s.p1_Pa.size(); ++e) {
    s.strip_F1_N[model.element_column[e]] += s.p1_Pa[e] * model.element_area_m2;
    s.strip_F2_N[model.element_column[e]] += s.p2_Pa[e] * model.element_area_m2;
  }
  s.p1_Pa.clear();
  s.p2_Pa.clear();
  s.slip.clear();
}

}  // namespace

TangentialSolution TangentialModel::solve(const Creepage& creepage, double mu, TangentialOutput output) const {
  TangentialSolution s = impl_->solve(creepage, mu, output);
  if (output == TangentialOutput::strip_forces) strip_sums_from_fields(*impl_, s);
  return s;
}

TangentialSolution TangentialModel::solve(const StripCreepages& creepages, double mu, TangentialOutput output) const {
  TangentialSolution s = impl_->solve(creepages, mu, output);
  if (output == TangentialOutput::strip_forces) strip_sums_from_fields(*impl_, s);
  return s;
}

TangentialSolver TangentialModel::solver() const { return impl_->solver; }
std::optional<Flexibility> TangentialModel::flexibility() const { return impl_->flexibility; }
CreepageCoupling TangentialModel::coupling() const { return impl_->coupling; }
const std::string& TangentialModel::flexibility_source() const { return impl_->flexibility_source; }
int TangentialModel::preparation_krylov_iterations() const { return impl_->preparation_krylov_iterations; }
const NhFastSim* TangentialModel::nh_fastsim() const { return impl_->nh_fastsim; }
const NhFastSimPerLobe* TangentialModel::nh_fastsim_per_lobe() const { return impl_->per_lobe; }

}  // namespace railcontact
