#pragma once
// A named option value (a solver, a slip direction, a contact surface, ...) read by the library's
// parser, its error prefixed with the option: "--slip-direction: unknown slip direction 'x' (...)".
#include <fmt/core.h>

#include <string>

#include "railcontact/error.hpp"

namespace railcontact::cli {

template <class Parse>
auto parse_option_value(const char* option, const std::string& text, Parse parse) {
  try {
    return parse(text);
  } catch (const Error& e) {
    throw Error(fmt::format("{}: {}", option, e.what()));
  }
}

}  // namespace railcontact::cli
