#pragma once
// Outputs of a case run: the JSON document of `railcontact run --json`, and the files of
// `--out DIR` (tractions per element as CSV, the JSON, and figures drawn from them).
#include <filesystem>
#include <ostream>
#include <string>

#include "case/case_run.hpp"
#include "output/output_directory.hpp"

namespace railcontact {

// {"patch": {...}, "creepage": {...}, "results": {"<solver>": {"F1", "F2", "M3", "time_s",
//  "iterations", "flexibility": [L1, L2, L3] (FastSim solvers), ...}}}
std::string case_result_json(const CaseResult& result);

// A readable report: patch, creepage, one line per solver with the differences to exact.
void print_case_report(const CaseResult& result, std::ostream& out);

// Writes result.json, patch.csv (x1, x2, p3 per contact element), tractions_<solver>.csv
// (x1, x2, p3, p1, p2, |p|, slip) and the traction maps (tractions.png) into the directory.
// The files are staged in the locked output directory and committed at the end
// (output/output_directory.hpp): another run's directory is refused, an interrupted or failed write
// leaves the outputs of the last complete run.
void write_case_outputs(const CaseResult& result, const std::filesystem::path& directory, std::ostream& log);
// The same into an output directory the caller locked before the computation (run --out).
void write_case_outputs(const CaseResult& result, output::OutputDirectory& output, std::ostream& log);

}  // namespace railcontact
