// The names of the tangential models (TangentialSolver, tangential.hpp).
#include <fmt/core.h>

#include <string>
#include <string_view>

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
  std::string names;
  for (TangentialSolver s : kTangentialSolvers) {
    if (name == solver_name(s)) return s;
    names += fmt::format("{}{}", names.empty() ? "" : ", ", solver_name(s));
  }
  throw Error(fmt::format("unknown solver '{}' (solvers: {})", name, names));
}

TangentialSolver tangential_solver_of(int value, std::string_view what, std::string_view kind) {
  std::string allowed;
  for (TangentialSolver s : kTangentialSolvers) {
    if (value == static_cast<int>(s)) return s;
    allowed += fmt::format("{}{} {}", allowed.empty() ? "" : ", ", static_cast<int>(s), solver_name(s));
  }
  throw Error(fmt::format("{} = {} is not {} ({})", what, value, kind, allowed));
}

}  // namespace railcontact
