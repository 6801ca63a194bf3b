#pragma once
// Stage: normal problem. Non-Hertzian normal contact on a regular mesh (docs/NORMAL.md,
// docs/METHOD.md §5) and the connected contact regions of its solution.
#include <cstddef>
#include <memory>
#include <string_view>
#include <vector>

#include "railcontact/contact_patch.hpp"

// The normal contact problem on a regular mesh (METHOD.md §5): given the undeformed distance
// h(x1, x2) between the two profiles at the element centres (X3 points into the wheel; h > 0
// means separated, h < 0 interpenetration before the approach) and the normal force F3, find
// the approach delta and the pressure p3 with
//   g = h - delta + A33 p3 >= 0,   p3 >= 0,   p3 g = 0   (every element),
//   sum_I S p3_I = F3                                    (S = dx1 dx2),
// A33 the normal influence coefficients of two quasi-identical half-spaces (METHOD.md §4).
//
// Method: Polonsky & Keer's constrained conjugate gradients (Wear 231, 1999, 206-219) on the
// zero-padded FFT operator, preconditioned by a stencil approximation of the inverse influence
// operator on the contact set, started from a Hertz-like pressure on an interpenetration region
// fitted to the load. See docs/NORMAL.md.


namespace railcontact {

struct NormalOptions {
  // Relative tolerance on the complementarity residual (see NormalSolution::residual). The
  // rounding level of the FFT product is ~1e-13: smaller tolerances cannot be met (the solver
  // then runs to max_iterations and reports converged = false).
  double tolerance = 1e-10;
  // Conjugate-gradient iterations (each one FFT product, two when the contact set changes).
  int max_iterations = 1000;
};

struct NormalSolution {
  std::vector<double> pressure_Pa;  // p3 per mesh element (0 outside contact)
  double approach_m = 0.0;          // delta
  double normal_force_N = 0.0;      // sum S p3 (equals the prescribed load)
  int iterations = 0;               // conjugate-gradient iterations
  bool converged = false;           // residual <= tolerance and the contact set stable
  // max( max_{p3>0} |g|, max_{p3=0} max(0, -g) ) / max_I (A33 p3)_I, from A33 p3 made by FFT at
  // most 64 recursive updates before (their rounding: about 1e-16 of max A33 p3 each; NORMAL.md).
  double residual = 0.0;
  std::size_t elements_in_contact = 0;  // elements with p3 > 0
  bool touches_border = false;          // a contact element lies on the outer row/column of the mesh
};

// Solves the normal problem above. undeformed_distance_m holds one h per mesh element (mesh
// index order, see Mesh). Non-convergence within max_iterations is reported (converged = false),
// not thrown. Throws railcontact::Error on bad input (kind invalid_input): invalid mesh or
// material, h of the wrong size or not finite, F3 outside [kMinimumNormalForce_N,
// kMaximumNormalForce_N] (1 N ... 1e7 N, contact_patch.hpp), options out of range; kind no_contact
// when no contact forms; kind not_converged when the iteration breaks down (a non-finite pressure
// or approach: nothing non-finite is ever returned).
NormalSolution solve_normal_contact(const Mesh& mesh, const std::vector<double>& undeformed_distance_m,
                                    double normal_force_N, const Material& material,
                                    const NormalOptions& options = {});

// The normal problem with the approach delta prescribed (see NormalContactSolver::solve_at_approach).
// Throws as solve_normal_contact, except that no contact is a valid answer (F3 = 0).
NormalSolution solve_normal_contact_at_approach(const Mesh& mesh, const std::vector<double>& undeformed_distance_m,
                                                double approach_m, const Material& material,
                                                const NormalOptions& options = {});

namespace detail {
struct NormalSolverAccess;  // a time step's start from known products (src/normal/known_product.hpp)
}

// The same solver as a reusable plan: the influence operator (kernel table, FFT plans) and the
// iteration workspace are built once for a mesh and material and reused by every solve()
// (e.g. along a wheel-rail contact sweep on a fixed mesh). Not thread-safe: one per thread.
class NormalContactSolver {
 public:
  NormalContactSolver(const Mesh& mesh, const Material& material, const NormalOptions& options = {});
  ~NormalContactSolver();
  NormalContactSolver(NormalContactSolver&&) noexcept;
  NormalContactSolver& operator=(NormalContactSolver&&) noexcept;
  NormalContactSolver(const NormalContactSolver&) = delete;
  NormalContactSolver& operator=(const NormalContactSolver&) = delete;

  [[nodiscard]] const Mesh& mesh() const;
  [[nodiscard]] NormalSolution solve(const std::vector<double>& undeformed_distance_m, double normal_force_N);
  // The approach delta prescribed instead of the load (a position-driven contact, e.g. a wheel at
  // a given position with h measured from it: delta = 0): F3 = sum S p3 follows. No element in
  // contact is a valid answer here (F3 = 0, no overlap). initial_pressure_Pa (mesh size, >= 0;
  // e.g. the previous solution of a time step on the same mesh) starts the iteration when given.
  [[nodiscard]] NormalSolution solve_at_approach(const std::vector<double>& undeformed_distance_m, double approach_m,
                                                 const std::vector<double>& initial_pressure_Pa = {});
  // The complementarity residual of NormalSolution::residual for a given pressure (mesh size,
  // >= 0) on this mesh, from one fresh product: how far it is from solving the problem with this
  // h and approach. Checks a solution found on a smaller mesh against the whole one. With
  // displacement_m given, the product u = A p (m, mesh order) is written there too.
  [[nodiscard]] double complementarity_residual(const std::vector<double>& undeformed_distance_m, double approach_m,
                                                const std::vector<double>& pressure_Pa,
                                                std::vector<double>* displacement_m = nullptr);

 private:
  friend struct detail::NormalSolverAccess;
  struct Plan;
  std::unique_ptr<Plan> plan_;
};

}  // namespace railcontact

// Connected contact regions of a normal solution: the elements with p3 > 0, grouped into
// 4-neighbour connected components (elements sharing an edge). A wheel-rail contact may form
// several separate patches (two-point contact, flange contact); docs/WHEEL_RAIL.md §5.


namespace railcontact {

struct ContactRegion {
  std::vector<std::size_t> elements;  // mesh indices, increasing
  double normal_force_N = 0.0;        // sum of S p3 over the region
  double load_fraction = 0.0;         // normal_force_N / total over all regions
  // Centre of pressure of the region in mesh coordinates.
  double x1_centre_m = 0.0;
  double x2_centre_m = 0.0;
};

// The regions sorted by decreasing normal force. pressure_Pa: one value per mesh element
// (elements with p3 > 0 are in contact). Throws Error if the sizes differ.
std::vector<ContactRegion> contact_regions(const Mesh& mesh, const std::vector<double>& pressure_Pa);

// A region carrying less than this fraction of the load is a speck of the discretisation, not a
// patch: a single-patch solve drops it (as the wheel-rail stage does).
inline constexpr double kSpeckLoadFraction = 0.01;

// The one contact patch of a body given by its undeformed distance on a grid (what a single-patch
// tangential solve needs, e.g. the C API's grid patch): the normal problem by load (or by approach:
// F3 follows), its regions found and specks dropped. `what` names the input in messages ("rc_patch
// grid"). Throws Error: as solve_normal_contact; not_converged when the normal solver does not
// converge; several_patches when more than one region carries over kSpeckLoadFraction of the load;
// at an approach, no_contact where no element touches and invalid_input when the force found lies
// outside the range of validate_normal_force.
struct GridPatch {
  ContactPatch patch;     // the region's elements and pressures (origin at its centre of pressure)
  NormalSolution normal;  // the whole grid's solution (specks included)
};
GridPatch single_grid_patch(const Mesh& mesh, const std::vector<double>& undeformed_distance_m, double normal_force_N,
                            const Material& material, const NormalOptions& options, std::string_view what);
GridPatch single_grid_patch_at_approach(const Mesh& mesh, const std::vector<double>& undeformed_distance_m,
                                        double approach_m, const Material& material, const NormalOptions& options,
                                        std::string_view what);

}  // namespace railcontact
