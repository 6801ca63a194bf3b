#pragma once
// Approximate inverse of the steady-rolling operator R = D A (D: upwind X1 difference,
// A: tangential influence; METHOD.md §6), used to precondition the Krylov solves of the
// adhesion and exact solvers. Two cheap factors, R^-1 = A^-1 D^-1:
//  1. D^-1 is FastSim's marching (paper Eq 2-3): along each strip run from the leading edge,
//     u_i = u_{i+1} - dx1 r_i with u = 0 ahead of the leading edge.
//  2. A^-1: the inverse of the 1/r half-space kernel acts like the half-Laplacian, Fourier
//     symbol ~|k| for k from ~pi/(patch size) to ~pi/dx. FastSim replaces it by a constant
//     1/L, which leaves a condition number ~ patch size / dx. Here it is replaced by
//     c0 - Laplacian_h (5-point stencil, zero outside the contact), whose symbol c0 + |k|^2
//     matches |k| up to a factor ~sqrt(size/dx) / 2 when c0 ~ k_min k_max
//     (c0 = gamma pi^2 / (size sqrt(dx1 dx2)), gamma = 3, tuned on ellipses a/b = 0.1..10).
// Measured (docs/BENCHMARKS.md): about half the GMRES iterations of the marching alone.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "railcontact/contact_patch.hpp"

namespace railcontact {

class SteadyRollingPreconditioner {
 public:
  // gamma <= 0: the marching factor alone (FastSim's constant flexibility instead of c0 - Laplacian).
  explicit SteadyRollingPreconditioner(const ContactElements& elements, double gamma = 3.0);
  // z = approximate R^-1 r; vectors [c1 on elements; c2 on elements].
  void apply(const double* r, double* z) const;
  // z = P^T r: the approximate inverse of R^T (adjoint solves).
  void apply_transpose(const double* r, double* z) const;
  // Only the marching factor (FastSim with L = 1): u = D^-1 r.
  void march(const double* r, double* u) const;
  // Its transpose: marching from the trailing edge towards the leading edge.
  void march_transpose(const double* r, double* u) const;

 private:
  std::size_t count_;
  void apply_stencil(const double* u, double* z) const;  // z = (c0 - Laplacian) u
  std::vector<std::uint8_t> ahead_in_contact_;  // the next element along +X1 is in contact
  // The stencil without branches (so that it vectorises): u is copied to padded_ = [0, u, 0], the
  // neighbours along X1 (e - 1, e + 1 when in contact) are weighted by 1 or 0, those along X2 are
  // read at their index in padded_ (0, the zero, when not in contact).
  std::vector<double> has_left_, has_right_;
  std::vector<std::uint32_t> down_, up_;
  // The marches run along strips; two independent halves of the elements (split at the start of a
  // strip run) are marched in lock-step, so that four dependency chains (two halves, two
  // components) overlap instead of two.
  std::size_t split_ = 0;
  double dx1_, inv_dx1_sq_, inv_dx2_sq_, c0_;
  mutable std::vector<double> work_, padded_;
};

}  // namespace railcontact
