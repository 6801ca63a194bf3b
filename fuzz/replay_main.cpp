// Replays inputs through a fuzz target without libFuzzer: `<target>_replay DIR_OR_FILE...` feeds
// every regular file (directories recursively, in name order; README.md and dot files skipped) to
// LLVMFuzzerTestOneInput, one at a time, and names each file before it runs, so that a crash, a
// hang (the ctest timeout) or an escaping exception is reported with its input. Built by the
// normal build (GCC) and run by ctest (label fuzz) on fuzz/corpus/<target>/ and
// fuzz/crashes/<target>/; under make test-sanitize with AddressSanitizer and UBSan.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <vector>

#include "fuzz_target.hpp"

namespace {

namespace fs = std::filesystem;

bool replayed(const fs::path& path) {
  const std::string name = path.filename().string();
  return !name.empty() && name[0] != '.' && name != "README.md";
}

// The files to replay under `argument`, sorted; throws when it does not exist.
std::vector<fs::path> inputs(const fs::path& argument) {
  std::vector<fs::path> files;
  if (fs::is_directory(argument)) {
    for (const fs::directory_entry& entry : fs::recursive_directory_iterator(argument))
      if (entry.is_regular_file() && replayed(entry.path())) files.push_back(entry.path());
  } else if (fs::is_regular_file(argument)) {
    files.push_back(argument);
  } else {
    throw std::runtime_error("no such file or directory: " + argument.string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: " << argv[0] << " DIR_OR_FILE...  (replays every file through the fuzz target)\n";
    return 2;
  }
  std::size_t count = 0;
  double slowest_s = 0.0;
  std::string slowest;
  for (int a = 1; a < argc; ++a) {
    std::vector<fs::path> files;
    try {
      files = inputs(argv[a]);
    } catch (const std::exception& e) {
      std::cerr << "replay: " << e.what() << "\n";
      return 2;
    }
    for (const fs::path& file : files) {
      std::cout << "replay: " << file.string() << std::endl;  // flushed: a crash or hang names its input
      std::ifstream in(file, std::ios::binary);
      const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      if (!in.eof() && in.fail()) {
        std::cerr << "replay: cannot read " << file.string() << "\n";
        return 2;
      }
      const auto start = std::chrono::steady_clock::now();
      try {
        LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
      } catch (const std::exception& e) {
        std::cerr << "replay: FAILED on " << file.string() << ": an exception escaped: " << e.what() << "\n";
        return 1;
      } catch (...) {
        std::cerr << "replay: FAILED on " << file.string() << ": an unknown exception escaped\n";
        return 1;
      }
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (seconds > slowest_s) {
        slowest_s = seconds;
        slowest = file.string();
      }
      ++count;
    }
  }
  std::cout << "replay: " << count << " inputs, no finding (slowest " << slowest_s << " s: " << slowest << ")\n";
  return 0;
}
