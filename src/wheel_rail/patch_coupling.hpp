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
// at most about s²/(12 r²), 2 % at the smallest distance between separate patches (the merge
// distance, 2 mm).
struct PressureBlocks {
  std::vector<Vector3> centre_m, normal;
  std::vector<double> force_N;
};
PressureBlocks pressure_blocks(const TangentPlaneArea& area, const SurfacePoints& points,
                               const std::vector<double>& pressure_Pa);

// Adds weight × the normal displacement the blocks' pressure causes at each element of `target`
// where the bodies overlap (h_m < 0; elsewhere no contact can arise, the coupling only lifting) to
// lift_m, along the target's normal: Σ (1 − ν)/(πG) F (n_source · n_target) / r.
void add_coupling_displacement(const PressureBlocks& source, const SurfacePoints& target, double weight,
                               const Material& material, const std::vector<double>& h_m, std::vector<double>& lift_m);

}  // namespace railcontact::detail
