#pragma once
// Figures of the studies: matplotlib scripts (scripts/*.py) run by Debian's /usr/bin/python3
// (RAILCONTACT_PYTHON) through scripts/figure_runner.py on the files a run wrote
// (docs/RELIABILITY.md "Outputs"). Everything the script prints is captured: the user sees one
// line at most, never a traceback.
// - A figure that cannot be written (a full disk, a quota, a file-size limit) is an output the
//   user asked for that is missing: Error(io) "cannot write the figure DIR/NAME.png: REASON"
//   (named as in the output directory, not the staging one).
// - A missing Python, matplotlib or script, or a script that fails otherwise, gives a warning on
//   `log`, not an error: the CSV files are the results, the figures are views of them.
#include <filesystem>
#include <ostream>
#include <string>

namespace railcontact::output {

// Runs scripts/<script> with the output directory as argument. Returns true when the figures are
// drawn, false after a warning; throws Error(io) when a figure cannot be written.
bool draw_figures(const std::string& script, const std::filesystem::path& directory, std::ostream& log);

}  // namespace railcontact::output
