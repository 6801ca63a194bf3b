#pragma once
// The contact window of a time step (docs/WHEELSET.md §8): the part of a potential contact area
// where the previous step's contact lay, widened by a margin. The normal problem is solved on the
// window only and the result checked on the whole area (one product there); the potential area is
// the overlap's bounding box, several times the contact (2.5x at y = 0, about 10x at y = -3 mm on
// S1002/UIC60), and its FFTs were most of a wheelset step.
#include <optional>
#include <vector>

#include "railcontact/contact_patch.hpp"

namespace railcontact::detail {

// A rectangle of a mesh's elements: columns lo1 .. lo1 + n1 - 1, rows lo2 .. lo2 + n2 - 1.
struct MeshWindow {
  int lo1 = 0, lo2 = 0, n1 = 0, n2 = 0;
};

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

}  // namespace railcontact::detail
