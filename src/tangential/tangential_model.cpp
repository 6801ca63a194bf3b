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
  std::optional<Flexibility> flexibility;
  std::string flexibility_source;
  int preparation_krylov_iterations = 0;
  const NhFastSim* nh_fastsim = nullptr;
  const NhFastSimPerLobe* per_lobe = nullptr;
};

}  // namespace detail

namespace {

using detail::TangentialModelImpl;

TangentialSolution from_fastsim(FastSimResult r, TangentialOutput output) {
  TangentialSolution s;
  s.forces = r.forces;
  s.adhesion_fraction = r.adhesion_fraction;
  if (output == TangentialOutput::fields) {
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

// FastSim with fixed flexibilities: classic FastSim (Eq 9, the parabolic bound of Eq 1) and
// nH-FastSim's fallback on a patch too small for K2 (Eq 9 with nH-FastSim's bound).
class FastSimModel final : public TangentialModelImpl {
 public:
  FastSimModel(FastSim fastsim, Flexibility L) : fastsim_(std::move(fastsim)), L_(L) { flexibility = L; }
  TangentialSolution solve(const Creepage& c, double mu, TangentialOutput output) const override {
    return from_fastsim(output == TangentialOutput::fields ? fastsim_.solve(c, L_, mu)
                                                           : fastsim_.forces_and_adhesion(c, L_, mu),
                        output);
  }
  TangentialSolution solve(const StripCreepages& c, double mu, TangentialOutput output) const override {
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
  }
  TangentialSolution solve(const Creepage& c, double mu, TangentialOutput output) const override {
    return from_fastsim(output == TangentialOutput::fields ? nh_.solve(c, mu) : nh_.forces_and_adhesion(c, mu),
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

void require_positive(double value, const char* field, const char* unit) {
  require(std::isfinite(value) && value > 0.0, [&] {
    return fmt::format("tangential model: {} = {}{} must be positive and finite", field, value, unit);
  });
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
              nh.bound.slip_direction == SlipDirection::rigid_slip,
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
  impl_ = std::move(model);
}

TangentialSolution TangentialModel::solve(const Creepage& creepage, double mu, TangentialOutput output) const {
  return impl_->solve(creepage, mu, output);
}

TangentialSolution TangentialModel::solve(const StripCreepages& creepages, double mu, TangentialOutput output) const {
  return impl_->solve(creepages, mu, output);
}

TangentialSolver TangentialModel::solver() const { return impl_->solver; }
std::optional<Flexibility> TangentialModel::flexibility() const { return impl_->flexibility; }
const std::string& TangentialModel::flexibility_source() const { return impl_->flexibility_source; }
int TangentialModel::preparation_krylov_iterations() const { return impl_->preparation_krylov_iterations; }
const NhFastSim* TangentialModel::nh_fastsim() const { return impl_->nh_fastsim; }
const NhFastSimPerLobe* TangentialModel::nh_fastsim_per_lobe() const { return impl_->per_lobe; }

}  // namespace railcontact
