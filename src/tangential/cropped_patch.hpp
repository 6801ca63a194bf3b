#pragma once
// A contact patch cut out of a potential-contact-area mesh: the bounding box of its elements in
// contact, so that the tangential solvers' FFTs cover the patch only (docs/WHEEL_RAIL.md §2).
#include <array>
#include <cstddef>
#include <optional>
#include <vector>

#include "railcontact/contact_patch.hpp"
#include "railcontact/normal.hpp"
#include "railcontact/tangential.hpp"

namespace railcontact::detail {

// Index bounding box of a set of mesh elements: lo1..hi1 along X1, lo2..hi2 along X2 (inclusive).
struct IndexBox {
  int lo1, hi1, lo2, hi2;
};
IndexBox bounding_box(const Mesh& mesh, const std::vector<std::size_t>& elements);

// The patch of the given elements (mesh indices) with their pressures, on the mesh cropped to
// their bounding box (same element size and positions). ContactPatch moves its origin to the
// centre of pressure. Throws Error when no element carries pressure.
ContactPatch cropped_patch(const Mesh& mesh, const std::vector<double>& pressure_Pa,
                           const std::vector<std::size_t>& elements, const Material& material);

// The same with the crop aligned to a block grid: the mesh's element centres lie at integer
// multiples of the element size from a reference point (as a wheelset patch's mesh does; another
// mesh is counted from its first element's nearest multiple, every element kept), and the
// crop starts at a multiple of the block's length from it along each axis and spans whole blocks. A
// patch coarsened in these blocks (coarsened()) then has its blocks fixed to the reference point, not
// to the patch's corner, so the coarse patch changes continuously as elements enter
// (docs/WHEELSET.md §6).
ContactPatch block_aligned_patch(const Mesh& mesh, const std::vector<double>& pressure_Pa,
                                 const std::vector<std::size_t>& elements, const Material& material,
                                 CoarseBlocks blocks);

// Whether a patch's elements form more than one 4-neighbour connected lobe (as contact_regions
// counts them), from its strip runs: runs of adjacent strips touch where their element ranges
// overlap. A union-find over its runs: 1.1 µs for a 4700-element patch (108 runs), where
// contact_regions on a wheelset's potential area takes ~110 µs (89 x 133 elements; both timed
// with throw-away loops, 2026-11-25).
bool has_several_lobes(const ContactPatch& patch);

// Necks: a patch of one connected lobe may still be two lobes joined by a narrow neck, such as the
// tread and the flange root of S1002 on UIC60 at y = −5.25 mm, 98.1 kN (lobes 96 and 62 elements
// wide joined by a neck of 5, at 0.17 mm elements). A strip (row of constant x2) is a neck of ratio
// r when it is r times as wide as the narrower of the widest strips on either side of it (r < 1: a
// valley in the strip widths; a patch whose widths rise and then fall has none). Up to
// kNeckWidthFraction the patch counts as two lobes cut at its narrowest neck (NhFastSimPerLobe);
// from kNeckBlendEnd on as one; in between NhFastSimPerLobe blends the two linearly in r, so that
// the forces do not jump where a widening neck stops being one.
inline constexpr double kNeckWidthFraction = 0.25;
inline constexpr double kNeckBlendEnd = 0.5;
// The smallest neck ratio of the patch's strips (from its strip runs); +infinity without a valley.
double neck_ratio(const ContactPatch& patch);
// Whether the patch has a neck of ratio at most kNeckWidthFraction.
bool has_neck(const ContactPatch& patch);
// The regions split at their necks of ratio at most `fraction`, recursively (the neck strip goes
// with the strips below it); each part's normal force, load fraction and centre of pressure
// recomputed, sorted by decreasing normal force. pressure_Pa: one value per mesh element.
std::vector<ContactRegion> split_at_necks(const Mesh& mesh, const std::vector<double>& pressure_Pa,
                                          std::vector<ContactRegion> regions, double fraction = kNeckWidthFraction);

// nH-FastSim's K2 needs a patch of some extent: below kMinimumElementsForK2 elements in contact
// (its spin coupling vanishes on a single strip), and below kFallbackElementsForK2 when the
// adhesion solve fails, a patch just appeared takes the equivalent ellipse's flexibilities
// (docs/WHEELSET.md §5). Shared by the wheelset and NhFastSimPerLobe.
inline constexpr std::size_t kMinimumElementsForK2 = 20;
inline constexpr std::size_t kFallbackElementsForK2 = 200;

// NhFastSim::automatic_coarsening and automatic_coarse_blocks from the number of elements in
// contact (a patch's elements().count()), for a caller that has not built the patch yet.
int automatic_coarsening(std::size_t elements_in_contact);
CoarseBlocks automatic_coarse_blocks(std::size_t elements_in_contact);

// nH-FastSim prepared on a patch by that rule: empty for a patch too small for K2, which then takes
// the equivalent ellipse's flexibilities. Throws what NhFastSim throws on a larger patch.
std::optional<NhFastSim> nh_fastsim_unless_too_small(const ContactPatch& patch, const NhFastSimOptions& options);

}  // namespace railcontact::detail
