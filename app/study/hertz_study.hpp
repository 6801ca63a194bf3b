#pragma once
// `railcontact study hertz`: creep curves up to full slip on Hertzian ellipses (a/b = 0.5, 1, 2)
// for pure xi, pure eta, pure phi and combined creepage, with all four solvers.
#include <filesystem>
#include <ostream>

namespace railcontact::study {

struct HertzStudyOptions {
  std::filesystem::path output_directory;
  int elements = 2000;
  int points = 10;  // creepage values per curve
  bool figures = true;
};

void run_hertz_study(const HertzStudyOptions& options, std::ostream& progress);

}  // namespace railcontact::study
