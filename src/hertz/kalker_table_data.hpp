#pragma once
// Kalker's creepage-coefficient table (Kalker 1990, Table E.3), compiled in from
// data/kalker_creepage_coefficients.csv by cmake/embed_kalker_table.cmake.
#include <span>

namespace railcontact::detail {

struct KalkerTableRow {
  double a_over_b;  // a = semi-axis along x1 (rolling direction)
  double nu;        // Poisson's ratio: 0, 0.25 or 0.5
  double c11, c22, c23;
};

std::span<const KalkerTableRow> kalker_table_rows();

}  // namespace railcontact::detail
