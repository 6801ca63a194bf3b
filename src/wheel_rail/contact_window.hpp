#pragma once
// The contact window of a time step (docs/WHEELSET.md §8): the part of a potential contact area
// where the previous step's contact lay, widened by a margin. The normal problem is solved on the
// window only and the result checked on the whole area (one product there); the potential area is
// the overlap's bounding box, several times the contact (2.5x at y = 0, about 10x at y = -3 mm on
// S1002/UIC60), and its FFTs were most of a wheelset step. While an earlier check on the whole area
// proves it, by a bound, the product there is left out (window_solution_holds_outside).
#include <optional>
#include <vector>

#include "railcontact/contact_patch.hpp"

namespace railcontact::detail {

// A rectangle of a mesh's elements: columns lo1 .. lo1 + n1 - 1, rows lo2 .. lo2 + n2 - 1.
struct MeshWindow {
  int lo1 = 0, lo2 = 0, n1 = 0, n2 = 0;
};

// The bounding box of the elements with pressure > 0; empty when none is.
std::optional<MeshWindow> pressure_support(const Mesh& mesh, const std::vector<double>& pressure_Pa);

// The window around the elements with pressure > 0, widened by `margin` elements on every side and
// then to a multiple of `granule` elements per axis (of the largest power of two g with 16 g <= its
// length when that is coarser; so that its size, and the solver plan it needs,
// changes seldom from step to step), within the mesh. Empty when no element carries pressure or the
// window's padded FFT grid would be more than `largest_fraction` of the mesh's (little to gain).
std::optional<MeshWindow> contact_window(const Mesh& mesh, const std::vector<double>& pressure_Pa, int margin,
                                         int granule, double largest_fraction);

// The window's own mesh: the same elements, at the same positions.
Mesh window_mesh(const Mesh& mesh, const MeshWindow& window);

// A mesh field's values in the window (window_mesh order), and back: the window's values on the whole
// mesh, zero outside the window.
std::vector<double> cut_window(const Mesh& mesh, const std::vector<double>& field, const MeshWindow& window);
std::vector<double> paste_window(const Mesh& mesh, const std::vector<double>& window_field, const MeshWindow& window);

// An element of the window's outer row or column that is not on the mesh's outer row or column
// carries pressure: the contact may reach beyond the window.
bool contact_on_inner_window_edge(const Mesh& mesh, const MeshWindow& window, const std::vector<double>& window_pressure_Pa);

// A patch's last check of a window solution on its whole potential area: the area's mesh, the
// pressure checked there and its product u = A p on that mesh (A: the half-space's normal
// influence coefficients A33, every one positive).
struct WholeAreaCheck {
  Mesh mesh;
  std::vector<double> pressure_Pa, displacement_m;
  // pressure_support(mesh, pressure_Pa), made with the check so that each step's test need not
  // scan the check's pressure; when absent, the test finds it.
  std::optional<std::optional<MeshWindow>> support;
};

// Upper bounds of A33 (m/Pa, elastic/influence_coefficients.hpp) between two elements d1 columns
// and d2 rows apart (d1, d2 >= 0), for one element size and material: the coefficient itself for
// offsets below kExact on both axes, beyond that the element's pressure taken as a force at the
// element's nearest corner, (1 − ν)/(πG) dx1 dx2 / (r − half the element's diagonal). A33 falls
// with either offset, so the bound at the nearest offsets of a group of elements bounds all of them.
class NormalInfluenceBound {
 public:
  NormalInfluenceBound(double dx1_m, double dx2_m, const Material& material);
  [[nodiscard]] bool fits(double dx1_m, double dx2_m, const Material& material) const {
    return dx1_m == dx1_m_ && dx2_m == dx2_m_ && material.youngs_modulus_Pa == material_.youngs_modulus_Pa &&
           material.poisson_ratio == material_.poisson_ratio;
  }
  [[nodiscard]] double at(int d1, int d2) const;

 private:
  static constexpr int kExact = 32;
  double dx1_m_, dx2_m_;
  Material material_;
  std::vector<double> exact_;  // [d2 * kExact + d1]
};

// True when a window's solution, `pressure_Pa` on the whole area's mesh (zero outside `window`),
// provably leaves no element outside the window overlapping: h + A p >= 0 there. It follows from
// an earlier check on the same patch, whose pressure p_c moved onto this mesh (element centres at
// whole multiples of the element size from the reference point, as WheelsetWarmStart moves
// pressures) gives, for every element k, A p(k) >= u_c(k) − max_j A(k − j) ||p − p_c||_1 (j over the
// elements where p and p_c differ), and from A p >= 0. False when the bound does not prove it (an
// overlapping element outside the window that the check's mesh does not cover, or a bound below
// zero), or when the check's pressure does not lie on this mesh: the whole area's product decides.
bool window_solution_holds_outside(const Mesh& mesh, const std::vector<double>& h_m, const MeshWindow& window,
                                   const std::vector<double>& pressure_Pa, const WholeAreaCheck& check,
                                   const NormalInfluenceBound& influence);

}  // namespace railcontact::detail
