#pragma once
// One exception type for every error the library reports: bad input, non-physical
// parameters, files that cannot be read, solvers that do not converge. The message names
// the problem in one line; the CLI prints it and exits with a non-zero code.
#include <concepts>
#include <stdexcept>
#include <string>

namespace railcontact {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws Error(message) unless condition holds. The message is built only on failure: a
// literal is passed as is, a composed message as a callable returning it, e.g.
//   require(mu > 0, [&] { return fmt::format("mu = {} must be positive", mu); });
// (checks inside solvers' hot paths then cost a comparison, not a string).
inline void require(bool condition, const char* message) {
  if (!condition) throw Error(message);
}
inline void require(bool condition, const std::string& message) {
  if (!condition) throw Error(message);
}
template <std::invocable MakeMessage>
void require(bool condition, MakeMessage&& make_message) {
  if (!condition) throw Error(std::string(make_message()));
}

}  // namespace railcontact
