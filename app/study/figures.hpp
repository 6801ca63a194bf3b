#pragma once
// Figures of the studies: matplotlib scripts (scripts/*.py) run by Debian's /usr/bin/python3
// on the CSV files a study wrote. A missing Python or matplotlib gives a warning, not an error:
// the CSV files are the results, the figures are views of them.
#include <filesystem>
#include <ostream>
#include <string>

namespace railcontact::study {

// Runs scripts/<script> with the output directory as argument. Returns true on success.
bool draw_figures(const std::string& script, const std::filesystem::path& directory, std::ostream& log);

}  // namespace railcontact::study
