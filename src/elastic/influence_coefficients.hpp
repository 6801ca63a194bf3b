#pragma once
// Elastic influence coefficients of two quasi-identical half-spaces (METHOD.md §4).
//
// A traction of unit density, constant over a rectangular element of size dx1 x dx2 centred
// at the origin, produces at the surface point (x1, x2) the relative displacement
//   u3 = A33 p3,   u1 = A11 p1 + A12 p2,   u2 = A21 p1 + A22 p2   (A21 = A12).
// They are the integrals over the element of the Boussinesq-Cerruti point-force kernels
// (Kalker's form for two bodies, twice the single-body values):
//   u3 = (1 - nu)/(pi G) P3 / r,
//   u1 = 1/(pi G) [((1 - nu)/r + nu x1^2/r^3) P1 + nu x1 x2/r^3 P2],
//   u2 = 1/(pi G) [nu x1 x2/r^3 P1 + ((1 - nu)/r + nu x2^2/r^3) P2],
// integrated in closed form (Love 1929; Johnson, Contact Mechanics §3.9) with the
// antiderivatives  ∫∫ 1/r = X asinh(Y/|X|) + Y asinh(X/|Y|),  ∫∫ X²/r³ = Y asinh(X/|Y|),
// ∫∫ Y²/r³ = X asinh(Y/|X|),  ∫∫ XY/r³ = -r  (the X ln|X| terms cancel between corners).
#include "railcontact/contact_patch.hpp"

namespace railcontact {

struct ElementSize {
  double dx1_m = 0.0;
  double dx2_m = 0.0;
};

// Normal displacement (m) at (x1, x2) per unit pressure (Pa) on the element: A33.
double normal_influence(double x1_m, double x2_m, ElementSize element, const Material& material);

struct TangentialInfluence {
  double a11 = 0.0;  // u1 per p1 (m/Pa)
  double a12 = 0.0;  // u1 per p2 = u2 per p1
  double a22 = 0.0;  // u2 per p2
};

// Tangential displacements at (x1, x2) per unit shear traction on the element.
TangentialInfluence tangential_influence(double x1_m, double x2_m, ElementSize element, const Material& material);

}  // namespace railcontact
