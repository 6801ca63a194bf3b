// Fuzz target: wheelset case files (app/case/wheelset_case.cpp, docs/CASE_FILES.md "Wheelset
// cases"). What `railcontact wheelset CASE.toml` does with the text before any solve: UTF-8 check,
// TOML parse, every section and key, the options' ranges (validate(WheelsetOptions)) and the
// state's (validate(WheelsetPosition)). Profile and set-up files named by a case are not read (their
// own targets cover them).
#include "case/wheelset_case.hpp"
#include "fuzz_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > (1u << 20)) return 0;  // read_wheelset_case refuses larger files before parsing
  railcontact::fuzz::expect_clean_outcome([&] {
    const railcontact::WheelsetCase c =
        railcontact::parse_wheelset_case(railcontact::fuzz::as_text(data, size), "fuzz.toml", "/fuzz");
    railcontact::validate(c.state.position);
  });
  return 0;
}
