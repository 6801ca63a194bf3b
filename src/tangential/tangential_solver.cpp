// The names of the tangential models (TangentialSolver, tangential.hpp).
#include <fmt/core.h>

#include <string>

#include "railcontact/error.hpp"
#include "railcontact/tangential.hpp"

namespace railcontact {

const char* solver_name(TangentialSolver solver) {
  switch (solver) {
    case TangentialSolver::nh_fastsim: return "nh-fastsim";
    case TangentialSolver::fastsim: return "fastsim";
    case TangentialSolver::exact: return "exact";
    case TangentialSolver::exact_regularised: return "exact-regularised";
  }
  return "?";
}

TangentialSolver parse_tangential_solver(const std::string& name) {
  for (TangentialSolver s : {TangentialSolver::nh_fastsim, TangentialSolver::fastsim, TangentialSolver::exact,
                             TangentialSolver::exact_regularised})
    if (name == solver_name(s)) return s;
  throw Error(fmt::format("unknown solver '{}' (solvers: nh-fastsim, fastsim, exact, exact-regularised)", name));
}

}  // namespace railcontact
