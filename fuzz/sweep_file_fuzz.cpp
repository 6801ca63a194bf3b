// Fuzz target: sweep files (app/case/sweep_file.cpp, docs/CASE_FILES.md "Sweep files"). What
// `railcontact sweep FILE` does with the text before any solve: the wheelset-case sections, [grid]
// or [[case]], every axis and value, the grid's size; then the first and last case's state. Profile
// and set-up files are not read (their own targets cover them).
#include "case/sweep_file.hpp"
#include "fuzz_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > (4u << 20)) return 0;  // read_sweep_file refuses larger files before parsing
  railcontact::fuzz::expect_clean_outcome([&] {
    const railcontact::SweepFile f = railcontact::parse_sweep_file(railcontact::fuzz::as_text(data, size), "fuzz.toml", "/fuzz");
    if (f.size() == 0) std::abort();  // an empty sweep must have been refused
    (void)f.at(0);
    (void)f.at(f.size() - 1);
  });
  return 0;
}
