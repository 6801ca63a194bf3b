#pragma once
// `railcontact study paper`: the paper's Section 4 on the S1002/UIC60 pair (METHOD.md §9):
// Fig 5 (total-force error vs y for three creepage families), Fig 6 (traction maps at y = 0),
// Fig 7 (F1 creep curves), Fig 8 (computing time vs elements in contact).
#include <filesystem>
#include <ostream>

namespace railcontact::study {

struct PaperStudyOptions {
  std::filesystem::path output_directory;
  int elements = 3000;           // elements in contact of every patch (Fig 5-7)
  double y_step_m = 0.5e-3;      // Fig 5: y from -4.5 to 4.5 mm
  int timing_samples = 10;       // Fig 8: random cases per mesh size
  bool figures = true;
  int threads = 1;               // Fig 5's y values on threads (the files do not depend on it)
};

void run_paper_study(const PaperStudyOptions& options, std::ostream& progress);

}  // namespace railcontact::study
