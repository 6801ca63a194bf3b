#pragma once
// Internal: the size limit of a flexibility table (kMaximumFlexibilityTableNodes,
// railcontact/flexibility_table.hpp), shared by the table's constructor and the file reader.
#include <cstddef>

namespace railcontact {

// Throws Error("flexibility table: 30000 y values × 100 loads = 3e+06 nodes; at most 2e+06 nodes
// are read …") when y_values × loads exceeds kMaximumFlexibilityTableNodes.
void check_table_size(std::size_t y_values, std::size_t loads);

}  // namespace railcontact
