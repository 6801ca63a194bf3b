# Turns data/kalker_creepage_coefficients.csv into a C++ array (run with cmake -P).
file(STRINGS ${INPUT} lines)
list(POP_FRONT lines header)
if(NOT header STREQUAL "a_over_b,nu,C11,C22,C23")
  message(FATAL_ERROR "${INPUT}: unexpected header '${header}'")
endif()
set(rows "")
set(count 0)
foreach(line IN LISTS lines)
  if(line STREQUAL "")
    continue()
  endif()
  string(REPLACE "," ";" fields "${line}")
  list(LENGTH fields n)
  if(NOT n EQUAL 5)
    message(FATAL_ERROR "${INPUT}: malformed line '${line}'")
  endif()
  list(JOIN fields ", " joined)
  string(APPEND rows "    {${joined}},\n")
  math(EXPR count "${count} + 1")
endforeach()
file(WRITE ${OUTPUT} "// Generated from data/kalker_creepage_coefficients.csv by cmake/embed_kalker_table.cmake.
// Kalker's Table E.3 (three significant digits); a = semi-axis in the rolling direction.
#include \"railcontact/kalker.hpp\"

namespace railcontact {
namespace {
const KalkerTableRow kRows[${count}] = {
${rows}};
}  // namespace

std::span<const KalkerTableRow> kalker_table_rows() { return kRows; }
}  // namespace railcontact
")
