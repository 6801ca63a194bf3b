#pragma once
// One exception type for every error the library reports: bad input, non-physical
// parameters, files that cannot be read, solvers that do not converge. The message names
// the problem in one line; the CLI prints it and exits with a non-zero code.
#include <stdexcept>
#include <string>

namespace railcontact {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws Error(message) unless condition holds.
inline void require(bool condition, const std::string& message) {
  if (!condition) throw Error(message);
}

}  // namespace railcontact
