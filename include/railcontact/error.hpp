#pragma once
// Errors of railcontact: one exception type, railcontact::Error, with a kind that says what went
// wrong, so that a caller can tell bad input from a case without contact, several contact patches
// where one is required, a solver that did not converge, or a file that cannot be read or written.
// The message names the problem in one line (the input, its value and what is allowed); the CLI
// prints it and exits with the code of its kind (docs/ARCHITECTURE.md "Errors").
#include <concepts>
#include <stdexcept>
#include <string>
#include <string_view>

namespace railcontact {

enum class ErrorKind {
  invalid_input,    // a value, an option or a file's content outside what is allowed
  no_contact,       // the bodies do not touch: no contact point, no element carries pressure
  several_patches,  // several contact patches where the computation needs one
  not_converged,    // an iterative solver did not reach its tolerance
  io,               // a file or directory cannot be read or written
  internal,         // an invariant of railcontact does not hold (a bug: please report it)
};

// "invalid input", "no contact", "several contact patches", "not converged", "input/output",
// "internal error".
std::string_view error_kind_name(ErrorKind kind);

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message, ErrorKind kind = ErrorKind::invalid_input)
      : std::runtime_error(message), kind_(kind) {}
  Error(ErrorKind kind, const std::string& message) : std::runtime_error(message), kind_(kind) {}
  Error(const Error&) = default;
  Error& operator=(const Error&) = default;
  // Defined in the library (its key function): the exception's type information lives in
  // librailcontact.so, so that a program catches what the shared library throws.
  ~Error() override;
  [[nodiscard]] ErrorKind kind() const noexcept { return kind_; }

 private:
  ErrorKind kind_;
};

// Throws Error(message) (kind invalid_input) unless condition holds. The message is built only on
// failure: a literal is passed as is, a composed message as a callable returning it, e.g.
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
