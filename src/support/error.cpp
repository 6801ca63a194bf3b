// The error type's key function and the names of the error kinds (railcontact/error.hpp).
#include "railcontact/error.hpp"

namespace railcontact {

Error::~Error() = default;

std::string_view error_kind_name(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::invalid_input: return "invalid input";
    case ErrorKind::no_contact: return "no contact";
    case ErrorKind::several_patches: return "several contact patches";
    case ErrorKind::not_converged: return "not converged";
    case ErrorKind::io: return "input/output";
    case ErrorKind::internal: return "internal error";
  }
  return "internal error";
}

}  // namespace railcontact
