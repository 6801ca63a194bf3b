#pragma once
// Runs a case end to end: patch -> (K2 -> flexibilities) -> the requested tangential solvers.
#include <Eigen/Core>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "railcontact/case.hpp"
#include "railcontact/kalker.hpp"
#include "railcontact/patch.hpp"

namespace railcontact {

struct SolverRun {
  SolverKind kind = SolverKind::exact;
  TangentialForces forces;
  double time_s = 0.0;                 // the whole solver, flexibilities included
  double flexibility_time_s = 0.0;     // part of time_s spent on the flexibilities (nh-fastsim: K2)
  int iterations = 0;                  // Newton (exact solvers), GMRES for K2 (nh-fastsim), 0 (fastsim)
  int krylov_iterations = 0;
  bool converged = true;
  std::optional<Flexibility> flexibility;  // FastSim solvers
  double adhesion_fraction = 0.0;
  // Per contact element (patch order):
  std::vector<double> p1_Pa, p2_Pa;
  std::vector<std::uint8_t> slip;
};

struct PatchSummary {
  std::string geometry;                // "ellipse" or "wheel-rail"
  double a_m = 0.0, b_m = 0.0;         // ellipse semi-axes, or the equivalent ellipse of a wheel-rail patch
  double normal_force_N = 0.0;
  double area_m2 = 0.0;
  double max_pressure_Pa = 0.0;
  std::size_t elements_in_contact = 0;
  int n1 = 0, n2 = 0;
  double dx1_m = 0.0, dx2_m = 0.0;
  double extent_x1_m = 0.0, extent_x2_m = 0.0;
  // Wheel-rail patches only:
  double lateral_displacement_m = 0.0, contact_angle_rad = 0.0, rolling_radius_m = 0.0, spin_per_m = 0.0;
};

struct CaseResult {
  Case input;
  ContactPatch patch;
  PatchSummary summary;
  Creepage creepage;                          // the raw creepages used (after normalisation)
  std::optional<Eigen::Matrix3d> creepage_matrix;  // K2 when nh-fastsim ran or normalisation needed it
  std::vector<SolverRun> runs;
  [[nodiscard]] const SolverRun* find(SolverKind kind) const;
};

// Throws railcontact::Error on bad input or a solver that does not converge. Progress lines go
// to `progress` when given.
CaseResult run_case(const Case& input, std::ostream* progress = nullptr);

// The built-in default case (`railcontact run` without a file).
Case default_case();

}  // namespace railcontact
