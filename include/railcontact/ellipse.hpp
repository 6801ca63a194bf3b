#pragma once
// An elliptical contact patch on a regular mesh: the mesh covers the bounding rectangle
// [-a, a] x [-b, b] with the same number of elements along both axes, and the elements whose
// centre lies inside the ellipse are in contact (paper §3).
#include "railcontact/mesh.hpp"

namespace railcontact {

// Mesh with n x n elements over the ellipse's bounding box.
ContactElements elliptical_contact(double a_m, double b_m, int elements_per_axis);

// The same with n chosen so that about target_elements lie inside (n = round(sqrt(4 N / pi))).
ContactElements elliptical_contact_with_count(double a_m, double b_m, int target_elements);

}  // namespace railcontact
