#pragma once
// Shared by the fuzz targets (fuzz/*_fuzz.cpp, docs/RELIABILITY.md "Fuzzing"): the input as text,
// and the rule every target checks. Bad input must end in a railcontact::Error of a kind other
// than `internal`; a crash, a hang, undefined behaviour, an internal error or any other exception
// escaping (std::bad_alloc, std::out_of_range, a parser's own exception) is a finding: it aborts,
// which libFuzzer and the replay driver (fuzz/replay_main.cpp) report with the input.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "railcontact/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace railcontact::fuzz {

inline std::string_view as_text(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

// Runs `parse`; a railcontact::Error is the expected outcome of bad input, except one of kind
// internal (a broken invariant of railcontact), which aborts like any other escaping exception.
template <class Parse>
void expect_clean_outcome(Parse&& parse) {
  try {
    parse();
  } catch (const Error& e) {
    if (e.kind() == ErrorKind::internal) {
      std::fprintf(stderr, "railcontact fuzz: internal error: %s\n", e.what());
      std::abort();
    }
  }
}

}  // namespace railcontact::fuzz
