#pragma once
// The regular mesh of the potential contact area (METHOD.md §3) and the set of elements in
// contact on it. Element (i1, i2) has its centre at
//   x1 = x1_first + i1 * dx1,  x2 = x2_first + i2 * dx2,
// and is stored at index i2 * n1 + i1: a strip (fixed x2, all x1) is contiguous, and x1 grows
// towards the leading edge (rolling direction +X1).
#include <cstddef>
#include <cstdint>
#include <vector>

namespace railcontact {

struct Mesh {
  int n1 = 0;             // elements along X1 (rolling direction)
  int n2 = 0;             // elements along X2 (lateral)
  double dx1_m = 0.0;     // element length along X1
  double dx2_m = 0.0;     // element width along X2
  double x1_first_m = 0.0;  // centre of the first element column
  double x2_first_m = 0.0;  // centre of the first element row

  [[nodiscard]] std::size_t size() const { return static_cast<std::size_t>(n1) * static_cast<std::size_t>(n2); }
  [[nodiscard]] std::size_t index(int i1, int i2) const {
    return static_cast<std::size_t>(i2) * static_cast<std::size_t>(n1) + static_cast<std::size_t>(i1);
  }
  [[nodiscard]] double x1(int i1) const { return x1_first_m + i1 * dx1_m; }
  [[nodiscard]] double x2(int i2) const { return x2_first_m + i2 * dx2_m; }
  [[nodiscard]] double element_area_m2() const { return dx1_m * dx2_m; }

  // Mesh of n1 x n2 elements exactly covering [x1_min, x1_max] x [x2_min, x2_max].
  static Mesh covering(double x1_min, double x1_max, double x2_min, double x2_max, int n1, int n2);
};

// Throws railcontact::Error unless the mesh has positive size and element lengths, and fits
// the memory budget of the solvers (at most max_elements elements).
void validate(const Mesh& mesh, std::size_t max_elements = 16u << 20);

// Elements in contact on a mesh: a flag per mesh element and the list of their indices in
// increasing order (strip by strip, each strip from trailing to leading edge).
class ContactElements {
 public:
  ContactElements() = default;
  ContactElements(const Mesh& mesh, std::vector<std::uint8_t> in_contact);

  [[nodiscard]] const Mesh& mesh() const { return mesh_; }
  [[nodiscard]] std::size_t count() const { return active_.size(); }
  [[nodiscard]] bool in_contact(std::size_t mesh_index) const { return flags_[mesh_index] != 0; }
  [[nodiscard]] const std::vector<std::uint8_t>& flags() const { return flags_; }
  // Mesh indices of the elements in contact.
  [[nodiscard]] const std::vector<std::size_t>& indices() const { return active_; }

 private:
  Mesh mesh_;
  std::vector<std::uint8_t> flags_;
  std::vector<std::size_t> active_;
};

}  // namespace railcontact
