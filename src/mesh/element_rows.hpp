#pragma once
// An element index k of a mesh n1 elements wide as its column and row (i1, i2) = (k mod n1, k / n1),
// with one division per row where the elements come row by row (as a patch's elements do, in
// increasing order): a 64-bit division costs tens of cycles, and the wheelset's time step walks
// each patch's ~5000 elements several times (docs/BENCHMARKS.md "Element rows without a division").
// Any order is accepted; an element outside the last row found costs a division.
#include <cstddef>

namespace railcontact::detail {

class ElementRows {
 public:
  explicit ElementRows(std::size_t n1) : n1_(n1) {}
  struct Place {
    int i1, i2;
  };
  [[nodiscard]] Place at(std::size_t k) {
    if (k < row_first_ || k - row_first_ >= n1_) {
      row_ = k / n1_;
      row_first_ = row_ * n1_;
    }
    return {static_cast<int>(k - row_first_), static_cast<int>(row_)};
  }

 private:
  std::size_t n1_;
  std::size_t row_ = 0, row_first_ = 0;  // the last row found and its first element's index
};

}  // namespace railcontact::detail
