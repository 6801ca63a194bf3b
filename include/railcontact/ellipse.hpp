#pragma once
// An elliptical contact patch on a regular mesh: the mesh covers the bounding rectangle
// [-a, a] x [-b, b] and the elements whose centre lies inside the ellipse are in contact
// (paper §3).
#include "railcontact/mesh.hpp"

namespace railcontact {

// How the bounding box is divided.
enum class EllipseMeshLayout {
  // n x n elements whatever a/b (the paper's meshes): elements are a/b times longer along X1
  // than across, coarse along the rolling direction when a > b.
  equal_counts,
  // dx1 = dx2 min(1, a/b): square elements when a >= b, the paper's layout when a < b, so the
  // rolling direction is never resolved more coarsely than the lateral one.
  rolling_resolved,
};

// Mesh with n1 x n2 elements over the bounding box.
ContactElements elliptical_contact(double a_m, double b_m, int n1, int n2);
// Mesh with n x n elements over the bounding box.
ContactElements elliptical_contact(double a_m, double b_m, int elements_per_axis);

// About target_elements inside the ellipse (pi/4 of the mesh), with the given layout.
ContactElements elliptical_contact_with_count(double a_m, double b_m, int target_elements,
                                              EllipseMeshLayout layout = EllipseMeshLayout::equal_counts);

}  // namespace railcontact
