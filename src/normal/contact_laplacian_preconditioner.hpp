#pragma once
// Preconditioner for the normal conjugate-gradient iteration (src/normal/constrained_cg.hpp):
// an approximate inverse of A33 restricted to the contact set Ic, applied by a 5-point stencil
// instead of an FFT.
//
// A33 is the discrete 1/r convolution (METHOD.md §4), Fourier symbol 2 (1 - nu)/(G |k|): its
// inverse acts like the half-Laplacian |k|, for k from ~pi / (patch size) to ~pi / dx. The
// stencil operator  M = c0 - Laplacian_h  on Ic (zero outside: Dirichlet at the contact edge)
// has symbol c0 + |k|^2, which matches |k| up to a factor ~sqrt(size / dx) / 2 when
// c0 ~ k_min k_max, i.e. c0 = gamma pi^2 / (size sqrt(dx1 dx2)), size = sqrt(area of Ic); the
// condition number of M A33 is then ~ the square root of that of A33. gamma = 2.5 was tuned on
// Hertzian cases (80 x 60 mesh, 3132 contact elements: 43 unpreconditioned iterations, 15 with
// gamma in [2, 3], 17 at gamma = 1 or 5). The same construction preconditions the tangential
// solvers (src/tangential/steady_rolling_preconditioner.hpp). M is symmetric positive definite
// on Ic, so conjugate gradients may use it.
// A time step's start, the last steps' pressures predicted (wheel_rail/wheelset_solver.cpp), is
// close: the error left lies at the contact's edges, where elements enter and leave, and a
// smaller gamma (kTimeStepGamma, 1), whose M weights the short wavelengths more, takes fewer
// iterations (docs/NORMAL.md "Preconditioner").
#include <cstddef>
#include <span>
#include <vector>

#include "railcontact/contact_patch.hpp"

namespace railcontact::detail {

class ContactLaplacianPreconditioner {
 public:
  static constexpr double kDefaultGamma = 2.5;
  static constexpr double kTimeStepGamma = 1.0;  // a time step's predicted start (by position)
  explicit ContactLaplacianPreconditioner(const Mesh& mesh, double gamma = kDefaultGamma);
  void set_gamma(double gamma) { gamma_ = gamma; }

  // z = (c0 - Laplacian_h) r on the elements with contact_mask = 1 (r taken as 0 where it is 0),
  // z = 0 elsewhere; c0 from the number of contact elements. Grid vectors (mesh size).
  void apply(std::span<const double> contact_mask, std::size_t contact_count, std::span<const double> r,
             std::span<double> z) const;

 private:
  Mesh mesh_;
  double gamma_;
  double inv_dx1_sq_, inv_dx2_sq_;
  // r on Ic and 0 elsewhere, with a row of zeros before and after the mesh's rows (the stencil's
  // neighbours beyond the mesh), so that the stencil's inner loop has no branch and vectorises.
  mutable std::vector<double> masked_;
};

}  // namespace railcontact::detail
