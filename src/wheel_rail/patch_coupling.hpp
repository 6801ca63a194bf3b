#pragma once
// The elastic coupling between a wheel's separate patches (docs/WHEELSET.md §5 "Coupled patches"):
// the pressure on one patch lifts the surfaces of the others, by the half-space's influence of a
// point load, (1 − ν)/(πG) P / r for two bodies of one material. Within a merged patch the mesh's own
// influence coefficients couple its parts; between separate patches the coupling is added to each
// patch's undeformed distance, with a weight that fades with the distance between their overlaps,
// so that the vertical force stays continuous where two overlaps come within the merge distance.
#include <vector>

#include "railcontact/wheelset.hpp"

namespace railcontact::detail {

// The weight of the coupling between two overlaps `distance_m` apart: 1 up to
// options.full_distance_m, 0 from options.end_distance_m on, a smoothstep between.
double patch_coupling_weight(double distance_m, const PatchCouplingOptions& options);

// The distance between two regions' overlaps in the track's cross-section (y, z): between their
// nearest ends, each end where the vertical gap crosses zero between two locus samples (linear in
// the gap, so continuous in the position). 0 for overlapping ranges.
double overlap_distance_m(const WheelContactSearch& search, const InterpenetrationRegion& a,
                          const InterpenetrationRegion& b);

// A contact surface's elements in the track frame: each element's centre and the surface's normal
// there (planar: the region's X3; conformal: its strip's normal).
struct SurfacePoints {
  std::vector<Vector3> point_m, normal;
};
SurfacePoints surface_points(const InterpenetrationRegion& region, const TangentPlaneArea& area);

// A patch's pressure gathered into blocks of about 1 mm (each block's force, its centre of force
// and mean normal): the source of the coupling. A block of side s as a point load errs in 1/r by
// about −s²/(24 r²) (against the mean of 1/r over the block), −0.5 % at 2 mm. Nearer than two
// blocks a target takes the block's elements one by one instead (two separate patches meeting at a
// neck of their overlap, docs/WHEELSET.md §3), each a point load, its distance no less than
// a = s_e / (4 ln(1 + √2)) for elements of side s_e: 1/a is the mean of 1/r over the element seen
// from its centre. Against that mean, an element's 1/max(r, a) errs by −17 % half an element from
// its centre, −3.7 % one element away and −1.0 % two away.
struct PressureBlocks {
  std::vector<Vector3> centre_m, normal;
  std::vector<double> force_N;
  // Block b's elements are elements [first_element[b], first_element[b + 1]).
  std::vector<std::size_t> first_element;
  std::vector<Vector3> element_point_m;
  std::vector<double> element_force_N;
  double element_core_m = 0.0;  // a above
};
PressureBlocks pressure_blocks(const TangentPlaneArea& area, const SurfacePoints& points,
                               const std::vector<double>& pressure_Pa);

// Adds weight × the normal displacement the blocks' pressure causes at each element of `target`
// where the bodies overlap (h_m < 0; elsewhere no contact can arise, the coupling only lifting) to
// lift_m, along the target's normal: Σ (1 − ν)/(πG) F (n_source · n_target) / r.
void add_coupling_displacement(const PressureBlocks& source, const SurfacePoints& target, double weight,
                               const Material& material, const std::vector<double>& h_m, std::vector<double>& lift_m);

}  // namespace railcontact::detail
