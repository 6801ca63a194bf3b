#pragma once
// A note for stderr ("note: ...") that a command prints when it ends without an error: a failing
// command keeps its one error line (docs/ARCHITECTURE.md "Errors"). Printed on scope exit unless
// an exception is propagating.
#include <fmt/core.h>

#include <cstdio>
#include <exception>
#include <string>
#include <utility>

namespace railcontact::cli {

class NoteOnSuccess {
 public:
  NoteOnSuccess() = default;
  explicit NoteOnSuccess(std::string text) : text_(std::move(text)) {}
  void set(std::string text) { text_ = std::move(text); }
  NoteOnSuccess(const NoteOnSuccess&) = delete;
  NoteOnSuccess& operator=(const NoteOnSuccess&) = delete;
  ~NoteOnSuccess() {
    if (!text_.empty() && std::uncaught_exceptions() == 0) fmt::print(stderr, "note: {}\n", text_);
  }

 private:
  std::string text_;
};

}  // namespace railcontact::cli
