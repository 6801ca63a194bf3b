#pragma once
// Comparing the results of two DIFFERENT code paths that are equal in exact arithmetic
// (docs/RELIABILITY.md "Reproducibility across CPUs"). FastSim's march that records the tractions
// (FastSim::solve, the CLI's `run`), its forces-only march (FastSim::forces, NhFastSim::forces) and
// the march that also counts the slipping elements (forces_and_adhesion: the C API and Python) are
// separate instantiations of one template, which the compiler vectorises and fuses into FMAs on
// its own: the order of the additions and the products it fuses depend on the instruction set and
// its tuning (-march). They agree to the last bit on one CPU and not on another (an Intel Xeon's
// AVX-512 code against an AMD's), so they are compared within a stated relative tolerance. The
// same path compared with itself (the same function called again, on other threads or MPI ranks,
// through the C API or the C++ API) stays bit for bit.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

namespace railcontact::test {

// 1e-12 of the force scale (mu F3, or |F|): a force is a sum of n <= ~1e4 element tractions, and
// reordering the sum or fusing a product moves it by a few ulps (1.1e-16) of the sum of |terms|,
// which is at most mu F3. Measured between the paths of the tests that use it, with FastSim
// compiled for icelake-server on an AMD EPYC (the CPU's own znver3 code gives 0): at most
// 3.6e-12 N on forces of 70-10000 N, 1.4e-15 of the value compared (a few ulps), ~1e3 below the
// tolerance.
constexpr double kDifferentPathsRelative = 1e-12;

// F1, F2 within kDifferentPathsRelative * force_scale_N and M3 within that times length_m (the
// patch's semi-axis: the lever arm of the tractions). A and B: TangentialForces, rc_forces.
template <class A, class B>
void expect_forces_near(const A& actual, const B& expected, double force_scale_N, double length_m,
                        const std::string& what = "") {
  const double tolerance_N = kDifferentPathsRelative * force_scale_N;
  EXPECT_NEAR(actual.F1_N, expected.F1_N, tolerance_N) << what;
  EXPECT_NEAR(actual.F2_N, expected.F2_N, tolerance_N) << what;
  EXPECT_NEAR(actual.M3_Nm, expected.M3_Nm, tolerance_N * length_m) << what;
}

}  // namespace railcontact::test
