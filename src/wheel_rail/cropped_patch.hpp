#pragma once
// A contact patch cut out of a potential-contact-area mesh: the bounding box of its elements in
// contact, so that the tangential solvers' FFTs cover the patch only (docs/WHEEL_RAIL.md §2).
#include <cstddef>
#include <vector>

#include "railcontact/contact_patch.hpp"

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

// The same with the crop aligned to a block grid: the mesh's element centres must lie at integer
// multiples of the element size from a reference point (as a wheelset patch's mesh does), and the
// crop starts at a multiple of `block` elements from it and spans whole blocks. A patch coarsened by
// `block` (coarsened()) then has its blocks fixed to the reference point, not to the patch's corner,
// so the coarse patch changes continuously as elements enter (docs/WHEELSET.md §6).
ContactPatch block_aligned_patch(const Mesh& mesh, const std::vector<double>& pressure_Pa,
                                 const std::vector<std::size_t>& elements, const Material& material, int block);

// Whether a patch's elements form more than one 4-neighbour connected lobe (as contact_regions
// counts them), from its strip runs: runs of adjacent strips touch where their element ranges
// overlap. A union-find over its runs: 1.1 µs for a 4700-element patch (108 runs), where
// contact_regions on a wheelset's potential area takes ~110 µs (89 x 133 elements; both timed
// with throw-away loops, 2026-11-25).
bool has_several_lobes(const ContactPatch& patch);

}  // namespace railcontact::detail
