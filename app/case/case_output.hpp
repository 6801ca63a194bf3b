#pragma once
// Outputs of a case run: the JSON document of `railcontact run --json`, and the files of
// `--out DIR` (tractions per element as CSV, the JSON, and figures drawn from them).
#include <filesystem>
#include <ostream>
#include <string>

#include "case/case_run.hpp"

namespace railcontact {

// {"patch": {...}, "creepage": {...}, "results": {"<solver>": {"F1", "F2", "M3", "time_s",
//  "iterations", "flexibility": [L1, L2, L3] (FastSim solvers), ...}}}
std::string case_result_json(const CaseResult& result);

// A readable report: patch, creepage, one line per solver with the differences to exact.
void print_case_report(const CaseResult& result, std::ostream& out);

// Writes result.json, patch.csv (x1, x2, p3 per contact element), tractions_<solver>.csv
// (x1, x2, p3, p1, p2, |p|, slip) and the traction maps (tractions.png) into the directory.
void write_case_outputs(const CaseResult& result, const std::filesystem::path& directory, std::ostream& log);

}  // namespace railcontact
