// nH-FastSim per lobe of a patch (include/railcontact/tangential.hpp, docs/WHEELSET.md §8): the
// patch split into its 4-neighbour connected lobes, each with its own flexibilities and the
// creepages at its own centre of pressure; forces summed, spin moment about the patch's origin.
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <utility>

#include <fmt/format.h>

#include "railcontact/error.hpp"
#include "railcontact/kalker.hpp"
#include "railcontact/tangential.hpp"
#include "railcontact/tangential_model.hpp"
#include "tangential/cropped_patch.hpp"
#include "tangential/lobe_sum.hpp"

namespace railcontact {

using detail::nh_fastsim_unless_too_small;
using detail::kMinimumElementsForK2;

struct NhFastSimPerLobe::Lobe {
  ContactPatch part;
  std::optional<NhFastSim> nh;  // empty: the equivalent-ellipse fallback below
  std::optional<FastSim> fallback;
  Flexibility fallback_flexibility;
  double x1_centre_m = 0.0, x2_centre_m = 0.0;  // its centre of pressure in the patch's coordinates
  std::vector<std::size_t> to_patch;            // element of `part` -> element of the patch

  Lobe(ContactPatch p, const NhFastSimOptions& options) : part(std::move(p)) {
    nh = nh_fastsim_unless_too_small(part, options);
    if (!nh) {
      const std::array<double, 2> ab = equivalent_ellipse_semi_axes(part);
      fallback_flexibility = fastsim_flexibility(ab[0], ab[1], part.material());
      fallback.emplace(part, options.bound);
    }
  }
  [[nodiscard]] FastSimResult solve(const Creepage& c, double mu) const {
    return nh ? nh->solve(c, mu) : fallback->solve(c, fallback_flexibility, mu);
  }
  [[nodiscard]] FastSimResult solve(const StripCreepages& c, double mu) const {
    return nh ? nh->solve(c, mu) : fallback->solve(c, fallback_flexibility, mu);
  }
};

NhFastSimPerLobe::NhFastSimPerLobe(const ContactPatch& patch, const NhFastSimOptions& options)
    : patch_elements_(patch.elements().count()) {
  const std::vector<std::size_t>& indices = patch.elements().indices();
  // The mesh the patch was cut from: its coordinates are the patch's minus its shift.
  Mesh source = patch.mesh();
  source.x1_first_m -= patch.x1_shift_m();
  source.x2_first_m -= patch.x2_shift_m();
  source_x2_first_m_ = source.x2_first_m;
  dx2_m_ = source.dx2_m;
  columns_ = source.n2;
  const auto whole_patch = [&] {
    Lobe lobe(patch, options);
    lobe.to_patch.resize(patch_elements_);
    for (std::size_t e = 0; e < patch_elements_; ++e) lobe.to_patch[e] = e;
    return lobe;
  };
  // Lobes apart (a gap between them): cut also at their necks up to kNeckWidthFraction. One
  // connected patch: cut at its narrowest neck below kNeckBlendEnd, and above kNeckWidthFraction
  // blended with the whole patch, linearly in the neck's ratio.
  const bool apart = detail::has_several_lobes(patch);
  const double ratio = apart ? 0.0 : detail::neck_ratio(patch);
  if (!apart && ratio >= detail::kNeckBlendEnd) {
    lobes_.push_back(whole_patch());
    return;
  }
  if (ratio > detail::kNeckWidthFraction) {
    whole_weight_ = (ratio - detail::kNeckWidthFraction) / (detail::kNeckBlendEnd - detail::kNeckWidthFraction);
    whole_.push_back(whole_patch());
  }
  const double cut = apart ? detail::kNeckWidthFraction : detail::kNeckBlendEnd;
  std::vector<double> pressure(source.size(), 0.0);
  std::vector<std::size_t> slot(source.size(), patch_elements_);  // mesh index -> element of the patch
  for (std::size_t e = 0; e < patch_elements_; ++e) {
    pressure[indices[e]] = patch.pressure_Pa()[e];
    slot[indices[e]] = e;
  }
  for (const ContactRegion& region : detail::split_at_necks(source, pressure, contact_regions(source, pressure), cut)) {
    ContactPatch part = detail::cropped_patch(source, pressure, region.elements, patch.material());
    if (options.flexibility_coarsening == 0 && part.elements().count() >= kMinimumElementsForK2) {
      // The aligned crop keeps the elements, so NhFastSim's automatic blocks are these.
      const CoarseBlocks blocks = NhFastSim::automatic_coarse_blocks(part);
      if (blocks != CoarseBlocks{1, 1})
        part = detail::block_aligned_patch(source, pressure, region.elements, patch.material(), blocks);
    }
    Lobe lobe(std::move(part), options);
    lobe.x1_centre_m = region.x1_centre_m + patch.x1_shift_m();
    lobe.x2_centre_m = region.x2_centre_m + patch.x2_shift_m();
    const ContactPatch& p = lobe.part;
    lobe.to_patch.resize(p.elements().count());
    for (std::size_t e = 0; e < p.elements().count(); ++e) {
      const auto i1 = static_cast<int>(std::lround((p.x1(e) - p.x1_shift_m() - source.x1_first_m) / source.dx1_m));
      const auto i2 = static_cast<int>(std::lround((p.x2(e) - p.x2_shift_m() - source.x2_first_m) / source.dx2_m));
      lobe.to_patch[e] = slot[source.index(i1, i2)];
    }
    lobes_.push_back(std::move(lobe));
  }
}

NhFastSimPerLobe::NhFastSimPerLobe(const NhFastSimPerLobe&) = default;
NhFastSimPerLobe::NhFastSimPerLobe(NhFastSimPerLobe&&) noexcept = default;
NhFastSimPerLobe& NhFastSimPerLobe::operator=(const NhFastSimPerLobe&) = default;
NhFastSimPerLobe& NhFastSimPerLobe::operator=(NhFastSimPerLobe&&) noexcept = default;
NhFastSimPerLobe::~NhFastSimPerLobe() = default;

template <typename CreepagesAtLobe>
FastSimResult NhFastSimPerLobe::solve_lobes(const CreepagesAtLobe& at_lobe, double mu) const {
  FastSimResult r;
  r.p1_Pa.assign(patch_elements_, 0.0);
  r.p2_Pa.assign(patch_elements_, 0.0);
  r.slip.assign(patch_elements_, 0);
  double adhesion_elements = 0.0;
  for (const Lobe& lobe : lobes_) {
    const FastSimResult s = lobe.solve(at_lobe(lobe), mu);
    detail::add_lobe(r.forces, s.forces, lobe.x1_centre_m, lobe.x2_centre_m);
    for (std::size_t e = 0; e < lobe.to_patch.size(); ++e) {
      const std::size_t to = lobe.to_patch[e];
      if (to == patch_elements_) continue;  // a zero-pressure element of a block-aligned crop
      r.p1_Pa[to] = s.p1_Pa[e];
      r.p2_Pa[to] = s.p2_Pa[e];
      r.slip[to] = s.slip[e];
    }
    adhesion_elements += s.adhesion_fraction * static_cast<double>(lobe.part.elements().count());
  }
  r.adhesion_fraction = adhesion_elements / static_cast<double>(patch_elements_);
  return r;
}

FastSimResult NhFastSimPerLobe::solve(const Creepage& creepage, double mu) const {
  if (lobes_.size() == 1) return lobes_.front().solve(creepage, mu);
  // The rigid slip (ξ − φ x2, η + φ x1) gives the creepages at a lobe's centre of pressure.
  FastSimResult r = solve_lobes(
      [&](const Lobe& lobe) { return detail::creepage_at(creepage, lobe.x1_centre_m, lobe.x2_centre_m); }, mu);
  if (whole_.empty()) return r;
  return blended_with_whole(std::move(r), whole_.front().solve(creepage, mu));
}

FastSimResult NhFastSimPerLobe::solve(const StripCreepages& creepages, double mu) const {
  require(creepages.size() == static_cast<std::size_t>(columns_), [&] {
    return fmt::format("nH-FastSim per lobe: {} strip creepages for a patch of {} columns", creepages.size(), columns_);
  });
  if (lobes_.size() == 1) return lobes_.front().solve(creepages, mu);
  // A lobe's columns are the patch's at the same x2 of the mesh both were cut from (a block-aligned
  // crop may reach a column beyond the patch's, of zero pressure: the nearest strip's); η moves to
  // the lobe's centre.
  FastSimResult r = solve_lobes(
      [&](const Lobe& lobe) {
        const Mesh& m = lobe.part.mesh();
        StripCreepages at(static_cast<std::size_t>(m.n2));
        for (int i2 = 0; i2 < m.n2; ++i2) {
          const double x2 = m.x2(i2) - lobe.part.x2_shift_m();
          const int j = std::clamp(static_cast<int>(std::lround((x2 - source_x2_first_m_) / dx2_m_)), 0, columns_ - 1);
          const Creepage& c = creepages[static_cast<std::size_t>(j)];
          at[static_cast<std::size_t>(i2)] = {c.xi, c.eta + c.phi * lobe.x1_centre_m, c.phi};
        }
        return at;
      },
      mu);
  if (whole_.empty()) return r;
  return blended_with_whole(std::move(r), whole_.front().solve(creepages, mu));
}

FastSimResult NhFastSimPerLobe::blended_with_whole(FastSimResult r, const FastSimResult& whole) const {
  // A neck between kNeckWidthFraction and kNeckBlendEnd: the per-lobe and the whole-patch
  // solutions blended (slip flags: the heavier one's).
  const double w = whole_weight_;
  r.forces = detail::blend(r.forces, whole.forces, w);
  for (std::size_t e = 0; e < patch_elements_; ++e) {
    r.p1_Pa[e] = detail::blend(r.p1_Pa[e], whole.p1_Pa[e], w);
    r.p2_Pa[e] = detail::blend(r.p2_Pa[e], whole.p2_Pa[e], w);
    if (w >= 0.5) r.slip[e] = whole.slip[e];
  }
  r.adhesion_fraction = detail::blend(r.adhesion_fraction, whole.adhesion_fraction, w);
  return r;
}

bool NhFastSimPerLobe::has_several_lobes(const ContactPatch& patch) {
  return detail::has_several_lobes(patch) || detail::neck_ratio(patch) < detail::kNeckBlendEnd;
}

std::size_t NhFastSimPerLobe::lobe_count() const { return lobes_.size(); }

NhFastSimPerLobe::LobeView NhFastSimPerLobe::lobe(std::size_t k) const {
  if (k >= lobes_.size())
    throw Error(fmt::format("NhFastSimPerLobe: lobe {} of a patch of {} lobes", k, lobes_.size()));
  const Lobe& l = lobes_[k];
  return {l.part, l.nh ? l.nh->flexibility() : l.fallback_flexibility, l.x1_centre_m, l.x2_centre_m,
          l.nh ? l.nh->coupling() : CreepageCoupling{}};
}

const Flexibility& NhFastSimPerLobe::flexibility() const {
  const Lobe& main = lobes_.front();  // contact_regions: by decreasing load
  return main.nh ? main.nh->flexibility() : main.fallback_flexibility;
}

CreepageCoupling NhFastSimPerLobe::coupling() const {
  const Lobe& main = lobes_.front();
  return main.nh ? main.nh->coupling() : CreepageCoupling{};
}

CreepageCoupling NhFastSimPerLobe::whole_patch_coupling() const {
  if (whole_.empty() || !whole_.front().nh) return {};
  return whole_.front().nh->coupling();
}

const Flexibility* NhFastSimPerLobe::whole_patch_flexibility() const {
  if (whole_.empty()) return nullptr;
  const Lobe& whole = whole_.front();
  return whole.nh ? &whole.nh->flexibility() : &whole.fallback_flexibility;
}

int NhFastSimPerLobe::coarsening() const {
  const Lobe& main = lobes_.front();
  return main.nh ? main.nh->coarsening() : 0;
}

int NhFastSimPerLobe::krylov_iterations() const {
  int n = 0;
  for (const Lobe& lobe : lobes_) n += lobe.nh ? lobe.nh->krylov_iterations() : 0;
  for (const Lobe& lobe : whole_) n += lobe.nh ? lobe.nh->krylov_iterations() : 0;
  return n;
}

}  // namespace railcontact
