#pragma once
// The contact patch shared by every tangential solver (FastSim, nH-FastSim, the adhesion and
// exact steady-rolling solvers): the mesh of the potential contact area, the elements in
// contact, the normal pressure p3 on them, the material, and the strip structure.
//
// Frame (METHOD.md §2): X1 rolling direction (leading edge at the largest x1), X2 lateral,
// X3 normal into the wheel; the origin is the centre of pressure, so the mesh coordinates of
// a patch are shifted to make sum(p3 x1) = sum(p3 x2) = 0.
#include <cstddef>
#include <vector>

#include "railcontact/material.hpp"
#include "railcontact/mesh.hpp"

namespace railcontact {

// One run of consecutive contact elements in one strip (row of the mesh at fixed x2). A strip
// may hold several runs when the patch is not convex along X1.
struct StripRun {
  int i2 = 0;                 // strip (row) index
  int i1_trailing = 0;        // first element of the run (smallest x1)
  int i1_leading = 0;         // last element of the run (largest x1), inclusive
  std::size_t first = 0;      // position of the trailing element in ContactElements::indices()
  double x1_trailing_m = 0;   // trailing edge: x1(i1_trailing) - dx1/2
  double x1_leading_m = 0;    // leading edge:  x1(i1_leading)  + dx1/2
  [[nodiscard]] int length() const { return i1_leading - i1_trailing + 1; }
};

class ContactPatch {
 public:
  ContactPatch() = default;
  // pressure_Pa: one value per mesh element; elements with p3 > 0 are in contact. The mesh is
  // re-centred on the centre of pressure. Throws railcontact::Error if no element carries
  // pressure or a value is negative or not finite.
  ContactPatch(const Mesh& mesh, const std::vector<double>& pressure_Pa, const Material& material);

  [[nodiscard]] const Mesh& mesh() const { return elements_.mesh(); }
  [[nodiscard]] const ContactElements& elements() const { return elements_; }
  [[nodiscard]] const Material& material() const { return material_; }
  // p3 on the elements in contact, in the order of elements().indices().
  [[nodiscard]] const std::vector<double>& pressure_Pa() const { return pressure_; }
  [[nodiscard]] const std::vector<StripRun>& runs() const { return runs_; }
  [[nodiscard]] double normal_force_N() const { return normal_force_N_; }
  [[nodiscard]] double area_m2() const { return static_cast<double>(elements_.count()) * mesh().element_area_m2(); }
  // Shift applied to the input mesh coordinates to put the origin at the centre of pressure.
  [[nodiscard]] double x1_shift_m() const { return x1_shift_m_; }
  [[nodiscard]] double x2_shift_m() const { return x2_shift_m_; }
  // Coordinates of contact element e (position in indices()).
  [[nodiscard]] double x1(std::size_t e) const { return mesh().x1(static_cast<int>(elements_.indices()[e] % mesh().n1)); }
  [[nodiscard]] double x2(std::size_t e) const { return mesh().x2(static_cast<int>(elements_.indices()[e] / mesh().n1)); }

 private:
  ContactElements elements_;
  Material material_;
  std::vector<double> pressure_;
  std::vector<StripRun> runs_;
  double normal_force_N_ = 0.0;
  double x1_shift_m_ = 0.0, x2_shift_m_ = 0.0;
};

// The patch on a mesh `factor` times coarser along both axes: each block of factor x factor
// elements becomes one element, in contact when at least half of its elements are, carrying the
// block's normal force (so the load and, nearly, the centre of pressure are kept). Used for
// cheaper nH-FastSim flexibilities: K2 and FastSim's adhesion terms depend only on the shape.
// factor in [1, kMaximumCoarsening].
inline constexpr int kMaximumCoarsening = 8;
ContactPatch coarsened(const ContactPatch& patch, int factor);

// Hertzian pressure p0 sqrt(1 - (x1/a)^2 - (x2/b)^2) on an elliptical patch (elements whose
// centre lies inside the ellipse), scaled so that the discrete normal force equals F3.
ContactPatch hertzian_patch(const ContactElements& ellipse, double a_m, double b_m, double normal_force_N,
                            const Material& material);

}  // namespace railcontact
