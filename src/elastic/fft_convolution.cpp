#include "elastic/fft_convolution.hpp"

#include <fftw3.h>

#include <algorithm>
#include <cstring>
#include <iterator>
#include <string>
#include <utility>

#include "railcontact/error.hpp"

namespace railcontact::detail {

template <typename T>
FftwArray<T>::FftwArray(std::size_t size) : data_(static_cast<T*>(fftw_malloc(sizeof(T) * size))), size_(size) {
  if (!data_) throw Error("FFT: out of memory for an array of " + std::to_string(size) + " values");
  std::memset(static_cast<void*>(data_.get()), 0, sizeof(T) * size);
}

template <typename T>
void FftwArray<T>::Free::operator()(T* p) const {
  fftw_free(p);
}

template class FftwArray<double>;
template class FftwArray<std::complex<double>>;

struct RealFft2d::Plans {
  Plans(int n1, int n2) {
    // Planned on scratch arrays (FFTW_ESTIMATE does not touch them), executed on others of the
    // same size and alignment. FFTW's row-major layout: n2 rows of n1 contiguous values.
    FftwArray<double> real(static_cast<std::size_t>(n1) * n2);
    FftwArray<std::complex<double>> spectrum(static_cast<std::size_t>(n2) * (n1 / 2 + 1));
    auto* complex = reinterpret_cast<fftw_complex*>(spectrum.data());
    forward = fftw_plan_dft_r2c_2d(n2, n1, real.data(), complex, FFTW_ESTIMATE);
    inverse = fftw_plan_dft_c2r_2d(n2, n1, complex, real.data(), FFTW_ESTIMATE);
    if (forward == nullptr || inverse == nullptr) {
      destroy();
      throw Error("FFT: FFTW could not plan the transform");
    }
  }
  ~Plans() { destroy(); }
  Plans(const Plans&) = delete;
  Plans& operator=(const Plans&) = delete;
  void destroy() {
    if (forward != nullptr) fftw_destroy_plan(forward);
    if (inverse != nullptr) fftw_destroy_plan(inverse);
  }
  fftw_plan forward = nullptr;
  fftw_plan inverse = nullptr;
};

namespace {

// The plans of the most recently used sizes on this thread (most recent last).
std::shared_ptr<const RealFft2d::Plans> plans_for(int n1, int n2) {
  constexpr std::size_t kKeptSizes = 16;
  struct Entry {
    int n1, n2;
    std::shared_ptr<const RealFft2d::Plans> plans;
  };
  thread_local std::vector<Entry> recent;
  for (auto it = recent.begin(); it != recent.end(); ++it) {
    if (it->n1 == n1 && it->n2 == n2) {
      Entry hit = std::move(*it);
      recent.erase(it);
      recent.push_back(std::move(hit));
      return recent.back().plans;
    }
  }
  if (recent.size() == kKeptSizes) recent.erase(recent.begin());
  recent.push_back({n1, n2, std::make_shared<const RealFft2d::Plans>(n1, n2)});
  return recent.back().plans;
}

}  // namespace

RealFft2d::RealFft2d(int n1, int n2) : n1_(n1), n2_(n2), plans_(plans_for(n1, n2)) {}

void RealFft2d::forward(const double* real, std::complex<double>* spectrum) const {
  // FFTW's r2c transforms leave their input intact (no FFTW_DESTROY_INPUT for r2c).
  fftw_execute_dft_r2c(plans_->forward, const_cast<double*>(real), reinterpret_cast<fftw_complex*>(spectrum));
}

void RealFft2d::inverse(std::complex<double>* spectrum, double* real) const {
  fftw_execute_dft_c2r(plans_->inverse, reinterpret_cast<fftw_complex*>(spectrum), real);
}

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
      fft_(fft_friendly_length(2 * n1 - 1), fft_friendly_length(2 * n2 - 1)),
      sum_(fft_.spectrum_size()) {
  const int N1 = fft_.n1();
  const int N2 = fft_.n2();
  const double normalisation = 1.0 / (static_cast<double>(N1) * N2);
  for (int c = 0; c < components; ++c) {
    inputs_.emplace_back(fft_.real_size());
    outputs_.emplace_back(fft_.real_size());
    input_spectra_.emplace_back(fft_.spectrum_size());
  }
  kernel_spectra_.resize(static_cast<std::size_t>(components * components));
  double* real = outputs_[0].data();  // scratch until the first product
  for (int k = 0; k < components; ++k) {
    for (int l = 0; l < components; ++l) {
      FftwArray<std::complex<double>>& spectrum = kernel_spectra_[static_cast<std::size_t>(k * components + l)];
      if (symmetric_blocks && l < k) {  // K_kl = K_lk: already transformed
        spectrum = FftwArray<std::complex<double>>(fft_.spectrum_size());
        const auto& same = kernel_spectra_[static_cast<std::size_t>(l * components + k)];
        std::copy_n(same.data(), same.size(), spectrum.data());
        continue;
      }
      std::fill(real, real + fft_.real_size(), 0.0);
      // Offset m is stored at m mod N (wrap-around order).
      for (int m2 = -(n2 - 1); m2 <= n2 - 1; ++m2) {
        const int j2 = m2 < 0 ? m2 + N2 : m2;
        for (int m1 = -(n1 - 1); m1 <= n1 - 1; ++m1) {
          const int j1 = m1 < 0 ? m1 + N1 : m1;
          real[static_cast<std::size_t>(j2) * N1 + j1] = kernel(k, l, m1, m2) * normalisation;
        }
      }
      spectrum = FftwArray<std::complex<double>>(fft_.spectrum_size());
      fft_.forward(real, spectrum.data());
    }
  }
}

void FftConvolution::clear_inputs() {
  const std::size_t stride = row_stride();
  for (FftwArray<double>& in : inputs_)
    for (int i2 = 0; i2 < n2_; ++i2) std::fill_n(in.data() + static_cast<std::size_t>(i2) * stride, n1_, 0.0);
}

void FftConvolution::convolve(bool transpose) {
  for (int l = 0; l < components_; ++l)
    fft_.forward(inputs_[static_cast<std::size_t>(l)].data(), input_spectra_[static_cast<std::size_t>(l)].data());
  const std::size_t ns = fft_.spectrum_size();
  std::complex<double>* acc = sum_.data();
  for (int k = 0; k < components_; ++k) {
    // Products written out on (re, im) pairs: std::complex's operator* guards against NaN
    // (C99 Annex G) and does not vectorise. The transposed kernel's spectrum is conj(K).
    const double sign = transpose ? -1.0 : 1.0;
    double* a = reinterpret_cast<double*>(acc);
    for (int l = 0; l < components_; ++l) {
      const auto* K = reinterpret_cast<const double*>(
          kernel_spectra_[static_cast<std::size_t>(transpose ? l * components_ + k : k * components_ + l)].data());
      const auto* P = reinterpret_cast<const double*>(input_spectra_[static_cast<std::size_t>(l)].data());
      const bool first = l == 0;
      for (std::size_t q = 0; q < 2 * ns; q += 2) {
        const double kr = K[q], ki = sign * K[q + 1], pr = P[q], pi = P[q + 1];
        const double re = kr * pr - ki * pi, im = kr * pi + ki * pr;
        a[q] = first ? re : a[q] + re;
        a[q + 1] = first ? im : a[q + 1] + im;
      }
    }
    fft_.inverse(acc, outputs_[static_cast<std::size_t>(k)].data());
  }
}

void FftConvolution::apply(std::span<const double> in, std::span<double> out) {
  const std::size_t n = grid_size();
  require(in.size() == n * components_ && out.size() == n * components_, "FFT convolution: wrong field size");
  const std::size_t stride = row_stride();
  for (int c = 0; c < components_; ++c) {
    const double* field = in.data() + static_cast<std::size_t>(c) * n;
    double* padded = input(c);
    for (int i2 = 0; i2 < n2_; ++i2)
      std::copy_n(field + static_cast<std::size_t>(i2) * n1_, n1_, padded + static_cast<std::size_t>(i2) * stride);
  }
  convolve(false);
  for (int c = 0; c < components_; ++c) {
    double* field = out.data() + static_cast<std::size_t>(c) * n;
    const double* padded = output(c);
    for (int i2 = 0; i2 < n2_; ++i2)
      std::copy_n(padded + static_cast<std::size_t>(i2) * stride, n1_, field + static_cast<std::size_t>(i2) * n1_);
  }
}

}  // namespace railcontact::detail
