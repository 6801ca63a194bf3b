#include "elastic/fft_convolution.hpp"

#include <fftw3.h>

#include <algorithm>
#include <new>
#include <utility>

#include "railcontact/error.hpp"

namespace railcontact::detail {

RealFft2d::RealFft2d(int n1, int n2) : n1_(n1), n2_(n2) {
  const std::size_t real_size = static_cast<std::size_t>(n1) * n2;
  real_ = static_cast<double*>(fftw_malloc(sizeof(double) * real_size));
  spectrum_ = static_cast<std::complex<double>*>(fftw_malloc(sizeof(fftw_complex) * spectrum_size()));
  if (real_ == nullptr || spectrum_ == nullptr) {
    fftw_free(real_);
    fftw_free(spectrum_);
    throw Error("FFT: out of memory for a " + std::to_string(n1) + " x " + std::to_string(n2) + " transform");
  }
  // FFTW's row-major layout: n2 rows of n1 contiguous values.
  auto* spectrum = reinterpret_cast<fftw_complex*>(spectrum_);
  plan_forward_ = fftw_plan_dft_r2c_2d(n2, n1, real_, spectrum, FFTW_ESTIMATE);
  plan_inverse_ = fftw_plan_dft_c2r_2d(n2, n1, spectrum, real_, FFTW_ESTIMATE);
  if (plan_forward_ == nullptr || plan_inverse_ == nullptr) throw Error("FFT: FFTW could not plan the transform");
}

RealFft2d::RealFft2d(RealFft2d&& other) noexcept
    : n1_(other.n1_),
      n2_(other.n2_),
      real_(std::exchange(other.real_, nullptr)),
      spectrum_(std::exchange(other.spectrum_, nullptr)),
      plan_forward_(std::exchange(other.plan_forward_, nullptr)),
      plan_inverse_(std::exchange(other.plan_inverse_, nullptr)) {}

RealFft2d::~RealFft2d() {
  if (plan_forward_ != nullptr) fftw_destroy_plan(static_cast<fftw_plan>(plan_forward_));
  if (plan_inverse_ != nullptr) fftw_destroy_plan(static_cast<fftw_plan>(plan_inverse_));
  fftw_free(real_);
  fftw_free(spectrum_);
}

void RealFft2d::forward() { fftw_execute(static_cast<fftw_plan>(plan_forward_)); }
void RealFft2d::inverse() { fftw_execute(static_cast<fftw_plan>(plan_inverse_)); }

int smooth_length(int minimum) {
  for (int n = std::max(minimum, 1);; ++n) {
    int m = n;
    for (int p : {2, 3, 5, 7}) {
      while (m % p == 0) m /= p;
    }
    if (m == 1) return n;
  }
}

int fft_friendly_length(int minimum) {
  // Lengths at which FFTW 3.3's FFTW_ESTIMATE plans of a real 2-D transform (forward and inverse)
  // are faster than at every longer length: the cheapest choice for any minimum up to 512
  // (measured on square transforms, docs/DEPENDENCIES.md "Padded lengths"). The smallest 7-smooth
  // length was up to 3x slower (35 and 45 against 36 and 48, 60 against 64, 120 against 128).
  static constexpr int kFastLengths[] = {16,  20,  32,  36,  42,  48,  56,  64,  72,  84,  90,  98,  100, 112,
                                         128, 140, 150, 160, 168, 200, 224, 256, 320, 384, 400, 448, 512};
  if (minimum <= 16 || minimum > 512) return smooth_length(minimum);
  return *std::lower_bound(std::begin(kFastLengths), std::end(kFastLengths), minimum);
}

FftConvolution::FftConvolution(int n1, int n2, int components, const KernelFunction& kernel,
                               bool symmetric_blocks)
    : n1_(n1),
      n2_(n2),
      components_(components),
      fft_(fft_friendly_length(2 * n1 - 1), fft_friendly_length(2 * n2 - 1)) {
  const int N1 = fft_.n1();
  const int N2 = fft_.n2();
  const double normalisation = 1.0 / (static_cast<double>(N1) * N2);
  kernel_spectra_.resize(static_cast<std::size_t>(components * components));
  for (int k = 0; k < components; ++k) {
    for (int l = 0; l < components; ++l) {
      if (symmetric_blocks && l < k) {  // K_kl = K_lk: already transformed
        kernel_spectra_[static_cast<std::size_t>(k * components + l)] =
            kernel_spectra_[static_cast<std::size_t>(l * components + k)];
        continue;
      }
      double* real = fft_.real();
      std::fill(real, real + static_cast<std::size_t>(N1) * N2, 0.0);
      // Offset m is stored at m mod N (wrap-around order).
      for (int m2 = -(n2 - 1); m2 <= n2 - 1; ++m2) {
        const int j2 = m2 < 0 ? m2 + N2 : m2;
        for (int m1 = -(n1 - 1); m1 <= n1 - 1; ++m1) {
          const int j1 = m1 < 0 ? m1 + N1 : m1;
          real[static_cast<std::size_t>(j2) * N1 + j1] = kernel(k, l, m1, m2) * normalisation;
        }
      }
      fft_.forward();
      kernel_spectra_[static_cast<std::size_t>(k * components + l)].assign(fft_.spectrum(),
                                                                            fft_.spectrum() + fft_.spectrum_size());
    }
  }
  input_spectra_.assign(static_cast<std::size_t>(components), std::vector<std::complex<double>>(fft_.spectrum_size()));
}

void FftConvolution::apply(std::span<const double> in, std::span<double> out) { apply(in, out, false); }

void FftConvolution::apply_transpose(std::span<const double> in, std::span<double> out) { apply(in, out, true); }

void FftConvolution::apply(std::span<const double> in, std::span<double> out, bool transpose) {
  const std::size_t n = grid_size();
  require(in.size() == n * components_ && out.size() == n * components_, "FFT convolution: wrong field size");
  const int N1 = fft_.n1();
  const std::size_t padded = static_cast<std::size_t>(N1) * fft_.n2();
  for (int l = 0; l < components_; ++l) {
    double* real = fft_.real();
    std::fill(real, real + padded, 0.0);
    const double* field = in.data() + static_cast<std::size_t>(l) * n;
    for (int i2 = 0; i2 < n2_; ++i2) {
      std::copy_n(field + static_cast<std::size_t>(i2) * n1_, n1_, real + static_cast<std::size_t>(i2) * N1);
    }
    fft_.forward();
    std::copy_n(fft_.spectrum(), fft_.spectrum_size(), input_spectra_[static_cast<std::size_t>(l)].data());
  }
  const std::size_t ns = fft_.spectrum_size();
  for (int k = 0; k < components_; ++k) {
    std::complex<double>* acc = fft_.spectrum();
    auto block = [&](int l) -> const std::vector<std::complex<double>>& {
      return kernel_spectra_[static_cast<std::size_t>(transpose ? l * components_ + k : k * components_ + l)];
    };
    const auto& K0 = block(0);
    const auto& P0 = input_spectra_[0];
    if (transpose) {
      for (std::size_t q = 0; q < ns; ++q) acc[q] = std::conj(K0[q]) * P0[q];
    } else {
      for (std::size_t q = 0; q < ns; ++q) acc[q] = K0[q] * P0[q];
    }
    for (int l = 1; l < components_; ++l) {
      const auto& K = block(l);
      const auto& P = input_spectra_[static_cast<std::size_t>(l)];
      if (transpose) {
        for (std::size_t q = 0; q < ns; ++q) acc[q] += std::conj(K[q]) * P[q];
      } else {
        for (std::size_t q = 0; q < ns; ++q) acc[q] += K[q] * P[q];
      }
    }
    fft_.inverse();
    double* field = out.data() + static_cast<std::size_t>(k) * n;
    const double* real = fft_.real();
    for (int i2 = 0; i2 < n2_; ++i2) {
      std::copy_n(real + static_cast<std::size_t>(i2) * N1, n1_, field + static_cast<std::size_t>(i2) * n1_);
    }
  }
}

}  // namespace railcontact::detail
