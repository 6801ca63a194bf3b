#pragma once
// A time step's normal solve started from products it already knows (docs/WHEELSET.md §8 "The
// start's product"): the wheelset predicts its start from the last steps' pressures, and the
// product A p of that prediction is the same combination of their products, so the solve's first
// product by FFT can be left out.
#include <vector>

#include "railcontact/normal.hpp"

namespace railcontact::detail {

// A pressure on a solver's mesh (Pa, any sign: a linear prediction) and its product A p (m), both in
// mesh order.
struct KnownProduct {
  std::vector<double> pressure_Pa;
  std::vector<double> displacement_m;
};

// What a solve's start is: a pressure given by itself (a user's, a height trial's at another
// approach, none), or a time step's prediction from the last steps' pressures, whose error lies at
// the contact's edges (the preconditioner then takes ContactLaplacianPreconditioner::
// kTimeStepGamma).
enum class StartKind { given, time_step_prediction };

struct NormalSolverAccess {
  // NormalContactSolver::solve_at_approach. With `known` given, the start (initial_pressure_Pa where
  // the bodies overlap) differs from known's pressure in at most
  // ConstrainedConjugateGradient::kLargestElementUpdate elements: its product is known's plus
  // those elements' differences by the kernel table, and no product by FFT starts the iteration
  // (otherwise one does). With final_product_m given, A p of the solution (m, mesh order, to
  // rounding) is written there.
  static NormalSolution solve_at_approach(NormalContactSolver& solver, const std::vector<double>& h, double approach_m,
                                          const std::vector<double>& initial_pressure_Pa, const KnownProduct* known,
                                          std::vector<double>* final_product_m,
                                          StartKind start = StartKind::given);
};

}  // namespace railcontact::detail
