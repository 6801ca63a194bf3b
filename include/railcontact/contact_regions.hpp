#pragma once
// Connected contact regions of a normal solution: the elements with p3 > 0, grouped into
// 4-neighbour connected components (elements sharing an edge). A wheel-rail contact may form
// several separate patches (two-point contact, flange contact); docs/WHEEL_RAIL.md §5.
#include <cstddef>
#include <vector>

#include "railcontact/mesh.hpp"

namespace railcontact {

struct ContactRegion {
  std::vector<std::size_t> elements;  // mesh indices, increasing
  double normal_force_N = 0.0;        // sum of S p3 over the region
  double load_fraction = 0.0;         // normal_force_N / total over all regions
  // Centre of pressure of the region in mesh coordinates.
  double x1_centre_m = 0.0;
  double x2_centre_m = 0.0;
};

// The regions sorted by decreasing normal force. pressure_Pa: one value per mesh element
// (elements with p3 > 0 are in contact). Throws Error if the sizes differ.
std::vector<ContactRegion> contact_regions(const Mesh& mesh, const std::vector<double>& pressure_Pa);

}  // namespace railcontact
