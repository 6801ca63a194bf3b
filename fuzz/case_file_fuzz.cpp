// Fuzz target: TOML case files (app/case/case_file.cpp, docs/CASE_FILES.md). What `railcontact run
// CASE.toml` does with the text before any solve: UTF-8 check, TOML parse, every section and key,
// then the case's values against the library's ranges (validate_case, as run_case does first).
// Profile files named by a wheel-rail case are not read (the profile targets cover them).
#include "case/case.hpp"
#include "case/case_run.hpp"
#include "fuzz_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > (1u << 20)) return 0;  // read_case_file refuses larger files before parsing
  railcontact::fuzz::expect_clean_outcome([&] {
    const railcontact::Case c = railcontact::parse_case(railcontact::fuzz::as_text(data, size), "fuzz.toml", "/fuzz");
    railcontact::validate_case(c);
  });
  return 0;
}
