#pragma once
// Kalker's linear theory of rolling contact for elliptical patches: the creepage coefficients
// C11, C22, C23 (Kalker 1990, Table E.3, compiled in from data/kalker_creepage_coefficients.csv)
// and the flexibility parameters of original FastSim (paper Eq 9).
#include <span>

#include "railcontact/contact_patch.hpp"

namespace railcontact {

struct KalkerCoefficients {
  double C11 = 0.0;
  double C22 = 0.0;
  double C23 = 0.0;
};

// Kalker's coefficients for semi-axis ratio a/b (a along X1) and Poisson's ratio nu in [0, 0.5]
// (nu = 0.5, incompressible, is the table's third column and is returned exactly):
// interpolated in the table for 0.1 <= a/b <= 10 (quadratic Lagrange in nu through 0, 0.25, 0.5;
// shape-preserving cubic (PCHIP) of ln C against ln(a/b); exact at the table's rows), Kalker's
// slender-ellipse asymptotes outside it (a/b in [0.01, 0.1) and (10, 100]), blended onto the table
// so that the coefficients are continuous at a/b = 0.1 and 10 (details in
// src/kalker/kalker_coefficients.cpp). Throws railcontact::Error for a/b or nu out of range.
KalkerCoefficients kalker_coefficients(double a_over_b, double nu);

// FastSim flexibility parameters (m/Pa), paper Eq 9.
struct Flexibility {
  double L1 = 0.0;  // longitudinal
  double L2 = 0.0;  // lateral
  double L3 = 0.0;  // spin
};

// Original FastSim flexibilities of an ellipse with semi-axes a (along X1) and b (Eq 9):
// L1 = 8a/(3 C11 G), L2 = 8a/(3 C22 G), L3 = pi a^1.5 / (4 sqrt(b) C23 G).
Flexibility fastsim_flexibility(double a_m, double b_m, const Material& material);

// Kalker's published table (Kalker 1990, Table E.3) that kalker_coefficients interpolates, compiled
// in from data/kalker_creepage_coefficients.csv: one row per (a/b, nu).
struct KalkerTableRow {
  double a_over_b;  // a = semi-axis along X1 (rolling direction)
  double nu;        // Poisson's ratio: 0, 0.25 or 0.5
  double c11, c22, c23;
};
std::span<const KalkerTableRow> kalker_table_rows();

}  // namespace railcontact
