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
#include <functional>
#include <memory>
#include <span>
#include <vector>

namespace railcontact::detail {

// FFTW buffers and plans, owned (RAII).
class RealFft2d {
 public:
  RealFft2d(int n1, int n2);  // n1 contiguous (x1), n2 rows (x2)
  ~RealFft2d();
  RealFft2d(const RealFft2d&) = delete;
  RealFft2d& operator=(const RealFft2d&) = delete;
  RealFft2d(RealFft2d&& other) noexcept;
  RealFft2d& operator=(RealFft2d&&) = delete;

  [[nodiscard]] int n1() const { return n1_; }
  [[nodiscard]] int n2() const { return n2_; }
  [[nodiscard]] std::size_t spectrum_size() const { return static_cast<std::size_t>(n2_) * (n1_ / 2 + 1); }
  double* real() { return real_; }
  std::complex<double>* spectrum() { return spectrum_; }
  void forward();   // real -> spectrum
  void inverse();   // spectrum -> real (unnormalised)

 private:
  int n1_, n2_;
  double* real_ = nullptr;
  std::complex<double>* spectrum_ = nullptr;
  void* plan_forward_ = nullptr;
  void* plan_inverse_ = nullptr;
};

// Smallest n >= minimum whose prime factors are 2, 3, 5, 7.
int smooth_length(int minimum);
// The padded transform length for a minimum length: the fastest length >= minimum for FFTW's
// estimated plans (a measured table up to 512, smooth_length beyond).
int fft_friendly_length(int minimum);

class FftConvolution {
 public:
  // kernel(k, l, m1, m2): block (k, l) of the kernel at index offset (m1, m2).
  using KernelFunction = std::function<double(int k, int l, int m1, int m2)>;

  // symmetric_blocks: K_kl = K_lk for all blocks (the caller knows; e.g. the half-space's
  // tangential blocks), so only the blocks k <= l are transformed.
  FftConvolution(int n1, int n2, int components, const KernelFunction& kernel, bool symmetric_blocks = false);

  [[nodiscard]] int components() const { return components_; }
  [[nodiscard]] std::size_t grid_size() const { return static_cast<std::size_t>(n1_) * n2_; }

  // in: components fields of grid_size() values each (component-major); out likewise.
  void apply(std::span<const double> in, std::span<double> out);
  // The transposed convolution, out_k(i) = sum_l sum_j K_lk(j - i) in_l(j): the same spectra,
  // conjugated and with the blocks swapped (a real kernel reversed in index has the conjugate
  // spectrum), so the adjoint costs exactly one product.
  void apply_transpose(std::span<const double> in, std::span<double> out);

 private:
  void apply(std::span<const double> in, std::span<double> out, bool transpose);

  int n1_, n2_, components_;
  RealFft2d fft_;
  std::vector<std::vector<std::complex<double>>> kernel_spectra_;  // [k * components + l]
  std::vector<std::vector<std::complex<double>>> input_spectra_;   // per component
};

}  // namespace railcontact::detail
