// Fuzz target: sweep and table-shard journals (app/study/sweep_journal.cpp, docs/SCALING.md), read
// when a sweep resumes and by `railcontact merge`: a malformed header is an Error, a damaged record
// ends the journal; every case read lies below the journal's case count.
#include <cstdlib>

#include "fuzz_target.hpp"
#include "study/sweep_journal.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  railcontact::fuzz::expect_clean_outcome([&] {
    const railcontact::study::SweepJournal j =
        railcontact::study::parse_sweep_journal(std::string(railcontact::fuzz::as_text(data, size)), "fuzz.journal", "fuzz");
    for (const auto& [k, r] : j.done)
      if (k >= j.header.cases) std::abort();
    if (j.valid_bytes > size) std::abort();
  });
  return 0;
}
