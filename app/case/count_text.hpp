#pragma once
// A count for a message (values along a grid, cases), computed in floating point from the inputs
// before any conversion to an integer: whole numbers below 1e15 as they are ("1002001000"), larger
// ones in three significant digits ("1e+300"), so that an absurd input (a step of 1e-300) does not
// print a 300-digit number.
#include <fmt/format.h>

#include <cmath>
#include <string>

namespace railcontact {

inline std::string count_text(double count) {
  if (std::isfinite(count) && std::fabs(count) < 1e15) return fmt::format("{:.0f}", count);
  return fmt::format("{:.3g}", count);
}

}  // namespace railcontact
