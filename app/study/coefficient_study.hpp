#pragma once
// `railcontact study coefficients`: the paper's Section 3 (Table 1, Fig 3, Fig 4) and beyond.
#include <filesystem>
#include <ostream>

namespace railcontact::study {

struct CoefficientStudyOptions {
  std::filesystem::path output_directory;
  int elements = 2800;       // elements in contact for Table 1
  int fine_elements = 11000; // the refined table
  bool figures = true;
  int threads = 1;           // Table 1's rows on threads (the tables do not depend on it)
};

// Writes table1.csv, table1_paper.csv, table1_fine.csv, fig3.csv, fig4.csv, figures and
// summary.md into the output directory; progress goes to `progress`.
void run_coefficient_study(const CoefficientStudyOptions& options, std::ostream& progress);

}  // namespace railcontact::study
