#pragma once
// Non-periodic 2-D convolution of grid fields with a small block of kernels, by zero-padded
// real FFTs (FFTW3). Used for every influence-times-traction product on a regular mesh
// (METHOD.md §4): out_k(i) = sum_l sum_j K_kl(i - j) in_l(j), i, j on an n1 x n2 grid.
//
// Kernels are given for index offsets m1 in [-(n1-1), n1-1], m2 in [-(n2-1), n2-1]; the
// padded transform length along each axis is at least 2n - 1 (fft_friendly_length), so the
// circular convolution equals the linear one on the grid.
#include <complex>
#include <cstddef>
#include <memory>
#include <span>
#include <vector>

namespace railcontact::detail {

// An FFTW-allocated array (SIMD-aligned, as FFTW's new-array execute requires), owned.
template <typename T>
class FftwArray {
 public:
  FftwArray() = default;
  explicit FftwArray(std::size_t size);  // zero-filled; throws railcontact::Error when out of memory
  [[nodiscard]] T* data() const { return data_.get(); }
  [[nodiscard]] std::size_t size() const { return size_; }

 private:
  struct Free {
    void operator()(T* p) const;
  };
  std::unique_ptr<T[], Free> data_;
  std::size_t size_ = 0;
};

// FFTW plans of one real 2-D transform size (n1 contiguous along x1, n2 rows), executed on any
// FftwArray of the right size (FFTW's new-array execute). Pruned for zero-padded convolutions:
// forward() reads only the first `rows` rows (the rest are taken as zero) and inverse() computes
// only the first `rows` rows, so the transforms along x1 of the padding rows are skipped
// (1.2-1.75x faster per forward + inverse pair with half the rows, docs/DEPENDENCIES.md).
// The spectrum is stored column by column: the n2 values of each of the n1 / 2 + 1 columns
// (wavenumbers k1) are contiguous. The transforms along x2 then read the row-major half spectrum
// with a stride and write contiguous columns (out of place, through a scratch array of the
// instance): 1.2-1.5x faster than in place with a stride both ways, and planned in 30-150 µs
// instead of 0.2-0.3 ms (docs/DEPENDENCIES.md "Spectrum layout"). Only element-wise products of
// spectra of the same layout are taken (FftConvolution), so the layout is internal.
// Plans are immutable and shared: the plans of the last 64 sizes are kept per thread (planning a
// known size again costs FFTW ~30 µs, 28 of the 35 µs of a 12 x 16 mesh's operator set-up,
// docs/DEPENDENCIES.md); this changes no result. An instance is used by one thread at a time
// (its scratch arrays).
class RealFft2d {
 public:
  RealFft2d(int n1, int n2, int rows);  // 0 < rows <= n2
  // The size and plans of `same` (shared: no planning, no lookup of the per-thread plans), scratch
  // arrays of its own (for another thread, or another buffer set of the same convolution).
  struct SharePlans {};
  RealFft2d(const RealFft2d& same, SharePlans);

  [[nodiscard]] int n1() const { return n1_; }
  [[nodiscard]] int n2() const { return n2_; }
  [[nodiscard]] std::size_t real_size() const { return static_cast<std::size_t>(n1_) * n2_; }
  [[nodiscard]] std::size_t spectrum_size() const { return static_cast<std::size_t>(n2_) * (n1_ / 2 + 1); }
  // real (n2 rows of n1, only the first `rows` rows read) -> spectrum (column by column); real
  // is not modified.
  void forward(const double* real, std::complex<double>* spectrum);
  // spectrum (column by column) -> the first `rows` rows of real, unnormalised; spectrum is not
  // modified. Of each row only the first n1 / 2 + 1 values are sure to be written (all that a
  // convolution of a grid of at most that many elements along x1 reads): small transforms
  // compute the inverse along x1 with the forward plan, which gives those (Plans in
  // fft_convolution.cpp).
  void inverse(const std::complex<double>* spectrum, double* real);
  // A field whose rows [rows, n2 - rows) are zero and the others possibly not (a kernel in
  // wrap-around order) -> spectrum, with this transform's own plans: its first and its last `rows`
  // rows in two passes of the row transform (a kernel then needs no plans of its own: planning is
  // most of a small convolution's first set-up in a process).
  void forward_wrapped(const double* real, std::complex<double>* spectrum) const;

  struct Plans;  // fft_convolution.cpp

 private:
  int n1_, n2_, rows_;
  std::shared_ptr<const Plans> plans_;
  // Row-major half spectra (n2 rows of n1 / 2 + 1) between the two passes: the forward one's
  // padding rows are zeroed once and never written; the inverse one is overwritten by each call.
  FftwArray<std::complex<double>> forward_rows_, inverse_rows_;
  FftwArray<double> hartley_rows_;  // the inverse through the forward plan: its real rows

  void inverse_rows_through_forward(double* real);
};

// Smallest n >= minimum whose prime factors are 2, 3, 5, 7.
int smooth_length(int minimum);
// The padded transform length for a minimum length: the fastest length >= minimum for FFTW's
// estimated plans (a measured table up to 512, smooth_length beyond).
int fft_friendly_length(int minimum);

// The spectra of a convolution's kernel blocks, [k * components + l] (immutable once made; shared
// by the convolutions with the same kernels).
using KernelSpectra = std::vector<FftwArray<std::complex<double>>>;

// The transform's rows run along x1 or x2, whichever layout FFTW estimates cheaper for the grid
// size (docs/FFT.md "Which axis the rows run along"); callers address the padded arrays through
// padded_index, so the layout is internal.
class FftConvolution {
 public:
  // kernel_table: components^2 blocks (k, l), k slowest, each (2 n2 - 1) rows of (2 n1 - 1)
  // values, block (k, l) of the kernel at index offsets m1 = -(n1-1)..n1-1 (fastest),
  // m2 = -(n2-1)..n2-1. symmetric_blocks: K_kl = K_lk for all blocks (the caller knows; e.g. the
  // half-space's tangential blocks), so only the blocks k <= l are transformed.
  FftConvolution(int n1, int n2, int components, std::span<const double> kernel_table, bool symmetric_blocks = false);
  // The kernels of another convolution of the same size (no tabulation, no transform), with
  // buffers of its own.
  FftConvolution(int n1, int n2, int components, std::shared_ptr<const KernelSpectra> kernel_spectra);
  // The kernels and the transforms' plans of `same` (shared), buffers of its own: neither
  // tabulation, transform nor planning (a convolution kept for its kernels, used by many threads
  // or calls, each with its own buffers).
  struct ShareKernels {};
  FftConvolution(const FftConvolution& same, ShareKernels);
  [[nodiscard]] const std::shared_ptr<const KernelSpectra>& kernel_spectra() const { return kernel_spectra_; }

  [[nodiscard]] int components() const { return components_; }
  [[nodiscard]] std::size_t grid_size() const { return static_cast<std::size_t>(n1_) * n2_; }

  // in: components fields of grid_size() values each (component-major); out likewise.
  void apply(std::span<const double> in, std::span<double> out);

  // In-place interface for callers that scatter and gather themselves: grid point (i1, i2) of
  // component c is input(c)[padded_index(i1, i2)], likewise output(c). clear_inputs() zeroes
  // the grid part of the inputs (the padding is never written and stays zero); convolve()
  // computes every output from the inputs; with transpose, those of the transposed convolution
  // out_k(i) = sum_l sum_j K_lk(j - i) in_l(j): the same spectra, conjugated and with the blocks
  // swapped (a real kernel reversed in index has the conjugate spectrum), at the same cost.
  [[nodiscard]] std::size_t padded_index(int i1, int i2) const {
    const auto row_length = static_cast<std::size_t>(fft_.n1());
    return rows_along_x2_ ? static_cast<std::size_t>(i1) * row_length + static_cast<std::size_t>(i2)
                          : static_cast<std::size_t>(i2) * row_length + static_cast<std::size_t>(i1);
  }
  // Whether the transform's rows run along x2 (x2 contiguous in the padded arrays) rather than
  // along x1: chosen per grid size by FFTW's estimate of the two layouts (fft_convolution.cpp).
  [[nodiscard]] bool rows_along_x2() const { return rows_along_x2_; }
  double* input(int component) { return inputs_[static_cast<std::size_t>(component)].data(); }
  [[nodiscard]] const double* output(int component) const { return outputs_[static_cast<std::size_t>(component)].data(); }
  void clear_inputs();
  void convolve(bool transpose);

 private:
  int n1_, n2_, components_;
  bool rows_along_x2_;
  RealFft2d fft_;  // rows along x1 (n1 = the padded length along x1) or, rows_along_x2_, along x2
  std::shared_ptr<const KernelSpectra> kernel_spectra_;          // [k * components + l]
  std::vector<FftwArray<double>> inputs_, outputs_;               // padded, per component
  std::vector<FftwArray<std::complex<double>>> input_spectra_;   // per component
  FftwArray<std::complex<double>> sum_;                          // spectrum of one output

  void allocate_buffers();
  static RealFft2d make_transform(int n1, int n2, bool rows_along_x2);
};

}  // namespace railcontact::detail
