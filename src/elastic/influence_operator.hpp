#pragma once
// Influence-times-traction products on a regular mesh (METHOD.md §4), restricted to a set of
// elements: y = M x, where x holds the traction components on the elements and y the
// displacement-type quantity at their collocation points. Two paths share one kernel table:
// a zero-padded FFT convolution (fast, O(N log N)) and a dense matrix (small problems, tests).
//
// Vectors are ordered component-major: [c0 on element 0..N-1, c1 on element 0..N-1, ...].
#include <Eigen/Dense>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "elastic/fft_convolution.hpp"
#include "railcontact/contact_patch.hpp"

namespace railcontact {

class InfluenceOperator {
 public:
  // From a precomputed kernel table: components^2 blocks, each (2 n2 - 1) x (2 n1 - 1), m1 fastest.
  InfluenceOperator(const Mesh& mesh, int components, std::vector<double> table);
  // The kernels of `same_kernels` (its table, spectra and FFT plans, shared) on `mesh`, which must have the
  // same n1, n2 and element size; buffers of its own. Costs no tabulation and no transform.
  InfluenceOperator(const Mesh& mesh, const InfluenceOperator& same_kernels);

  [[nodiscard]] const Mesh& mesh() const { return mesh_; }
  [[nodiscard]] int components() const { return components_; }
  [[nodiscard]] double kernel(int k, int l, int m1, int m2) const {
    return (*table_)[((static_cast<std::size_t>(k * components_ + l) * (2 * mesh_.n2 - 1) + (m2 + mesh_.n2 - 1)) *
                   (2 * mesh_.n1 - 1)) +
                  static_cast<std::size_t>(m1 + mesh_.n1 - 1)];
  }

  // Full-grid product: in and out hold components x mesh.size() values (zero where no traction).
  void apply_on_grid(std::span<const double> in, std::span<double> out);

  // out += K(· − element) value on the whole grid, for a single-component operator: the product of
  // a traction on one element, by the kernel table directly (mesh.size() multiply-adds; cheaper
  // than apply_on_grid for a few elements).
  void add_element_product(std::size_t element, double value, std::span<double> out) const;

  // Restricted product on the elements with the given mesh indices (FFT path).
  void apply(const std::vector<std::size_t>& elements, std::span<const double> x, std::span<double> y);

  // The transposed restricted product y = M^T x (kernel K'_kl(m) = K_lk(-m)), at the cost of
  // apply(): the transposed kernel's spectrum is the conjugate of the original's.
  void apply_transpose(const std::vector<std::size_t>& elements, std::span<const double> x, std::span<double> y);

  // Dense matrix of the restricted operator (reference path).
  [[nodiscard]] Eigen::MatrixXd dense(const std::vector<std::size_t>& elements) const;

 private:
  Mesh mesh_;
  int components_;
  std::shared_ptr<const std::vector<double>> table_;
  detail::FftConvolution convolution_;
  std::vector<std::uint32_t> padded_index_;  // mesh index -> index in the padded transform planes

  void apply(const std::vector<std::size_t>& elements, std::span<const double> x, std::span<double> y,
             bool transpose);
};

// Normal operator: surface approach u3 at element centres per unit pressure (A33).
InfluenceOperator make_normal_operator(const Mesh& mesh, const Material& material);

// Steady-rolling tangential operator R = (A(x + dx1) - A(x)) / dx1 (METHOD.md §6, Eq 10):
// the upwind (leading-edge side) difference along X1 of the tangential displacements, at
// collocation points offset by alpha dx1/2 from the element centres. In steady rolling the
// slip is s = V (w - R p) with w = (xi - phi x2, eta + phi x1).
InfluenceOperator make_steady_rolling_operator(const Mesh& mesh, const Material& material, double alpha);

}  // namespace railcontact
