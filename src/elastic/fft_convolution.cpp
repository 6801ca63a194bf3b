#include "elastic/fft_convolution.hpp"

#include <fftw3.h>

#include <algorithm>
#include <cstring>
#include <iterator>
#include <mutex>
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
  Plans(int n1, int n2, int rows) : n1(n1), n2(n2), rows(rows) {
    // Planned on scratch arrays (FFTW_ESTIMATE does not touch them), executed on others of the
    // same size and alignment. FFTW's row-major layout: n2 rows of n1 contiguous values.
    FftwArray<double> real(static_cast<std::size_t>(n1) * n2);
    FftwArray<std::complex<double>> spectrum(static_cast<std::size_t>(n2) * (n1 / 2 + 1));
    auto* complex = reinterpret_cast<fftw_complex*>(spectrum.data());
    if (rows == n2) {
      forward = fftw_plan_dft_r2c_2d(n2, n1, real.data(), complex, FFTW_ESTIMATE);
      inverse = fftw_plan_dft_c2r_2d(n2, n1, complex, real.data(), FFTW_ESTIMATE);
      check(forward != nullptr && inverse != nullptr);
      return;
    }
    // Pruned: the 1-D transforms along x1 of the rows that can be non-zero (forward) or are
    // wanted (inverse), and the transforms along x2 of every spectral column, in place.
    const int length1[] = {n1};
    const int length2[] = {n2};
    const int h = n1 / 2 + 1;
    forward =
        fftw_plan_many_dft_r2c(1, length1, rows, real.data(), nullptr, 1, n1, complex, nullptr, 1, h, FFTW_ESTIMATE);
    forward_columns =
        fftw_plan_many_dft(1, length2, h, complex, nullptr, h, 1, complex, nullptr, h, 1, FFTW_FORWARD, FFTW_ESTIMATE);
    inverse_columns =
        fftw_plan_many_dft(1, length2, h, complex, nullptr, h, 1, complex, nullptr, h, 1, FFTW_BACKWARD, FFTW_ESTIMATE);
    inverse =
        fftw_plan_many_dft_c2r(1, length1, rows, complex, nullptr, 1, h, real.data(), nullptr, 1, n1, FFTW_ESTIMATE);
    check(forward != nullptr && forward_columns != nullptr && inverse_columns != nullptr && inverse != nullptr);
  }
  ~Plans() { destroy(); }
  Plans(const Plans&) = delete;
  Plans& operator=(const Plans&) = delete;
  void check(bool planned) {
    if (planned) return;
    destroy();
    throw Error("FFT: FFTW could not plan the transform");
  }
  void destroy() {
    for (fftw_plan plan : {forward, forward_columns, inverse_columns, inverse})
      if (plan != nullptr) fftw_destroy_plan(plan);
  }
  int n1, n2, rows;
  fftw_plan forward = nullptr;          // 2-D, or along x1 on the first `rows` rows (pruned)
  fftw_plan forward_columns = nullptr;  // pruned only: along x2, every column, in place
  fftw_plan inverse_columns = nullptr;
  fftw_plan inverse = nullptr;
};

namespace {

// FFTW's planner (plan creation and destruction) is not thread-safe by itself; executing plans
// is. From the first plan on, FFTW serialises its planner, so solves may run on several threads.
void make_planner_thread_safe() {
  static std::once_flag once;
  std::call_once(once, [] { fftw_make_planner_thread_safe(); });
}

// The plans of the most recently used sizes on this thread (most recent last).
std::shared_ptr<const RealFft2d::Plans> plans_for(int n1, int n2, int rows) {
  constexpr std::size_t kKeptSizes = 16;
  thread_local std::vector<std::shared_ptr<const RealFft2d::Plans>> recent;
  for (auto it = recent.begin(); it != recent.end(); ++it) {
    if ((*it)->n1 == n1 && (*it)->n2 == n2 && (*it)->rows == rows) {
      std::shared_ptr<const RealFft2d::Plans> hit = std::move(*it);
      recent.erase(it);
      recent.push_back(std::move(hit));
      return recent.back();
    }
  }
  make_planner_thread_safe();
  if (recent.size() == kKeptSizes) recent.erase(recent.begin());
  recent.push_back(std::make_shared<const RealFft2d::Plans>(n1, n2, rows));
  return recent.back();
}

}  // namespace

RealFft2d::RealFft2d(int n1, int n2, int rows) : n1_(n1), n2_(n2), rows_(rows) {
  require(n1 > 0 && n2 > 0 && rows > 0 && rows <= n2, "FFT: invalid transform size");
  plans_ = plans_for(n1, n2, rows);
}

void RealFft2d::forward(const double* real, std::complex<double>* spectrum) const {
  // FFTW's r2c transforms leave their input intact (no FFTW_DESTROY_INPUT for r2c).
  auto* complex = reinterpret_cast<fftw_complex*>(spectrum);
  fftw_execute_dft_r2c(plans_->forward, const_cast<double*>(real), complex);
  if (rows_ == n2_) return;
  const std::size_t h = static_cast<std::size_t>(n1_ / 2 + 1);
  std::fill(spectrum + rows_ * h, spectrum + n2_ * h, std::complex<double>(0.0, 0.0));  // the zero rows' transforms
  fftw_execute_dft(plans_->forward_columns, complex, complex);
}

void RealFft2d::inverse(std::complex<double>* spectrum, double* real) const {
  auto* complex = reinterpret_cast<fftw_complex*>(spectrum);
  if (rows_ < n2_) fftw_execute_dft(plans_->inverse_columns, complex, complex);
  fftw_execute_dft_c2r(plans_->inverse, complex, real);
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
  // Lengths at which FFTW 3.3's FFTW_ESTIMATE plans of a pruned real 2-D transform (forward and
  // inverse, half the rows non-zero, as in every convolution here) are faster than at every
  // longer length: the cheapest choice for any minimum up to 512 (measured on square transforms,
  // docs/DEPENDENCIES.md "Padded lengths"). The smallest 7-smooth length was up to 3x slower
  // (35 and 45 against 36 and 48, 60 against 64, 120 against 128).
  static constexpr int kFastLengths[] = {16,  20,  32,  36,  42,  48,  64,  72,  84,  98,  100, 128,
                                         140, 150, 160, 168, 200, 256, 320, 384, 400, 448, 512};
  if (minimum <= 16 || minimum > 512) return smooth_length(minimum);
  return *std::lower_bound(std::begin(kFastLengths), std::end(kFastLengths), minimum);
}

FftConvolution::FftConvolution(int n1, int n2, int components, std::span<const double> kernel_table,
                               bool symmetric_blocks)
    : n1_(n1),
      n2_(n2),
      components_(components),
      fft_(fft_friendly_length(2 * n1 - 1), fft_friendly_length(2 * n2 - 1), n2),
      sum_(fft_.spectrum_size()) {
  const std::size_t w1 = static_cast<std::size_t>(2 * n1 - 1);
  const std::size_t w2 = static_cast<std::size_t>(2 * n2 - 1);
  require(kernel_table.size() == static_cast<std::size_t>(components * components) * w1 * w2,
          "FFT convolution: kernel table of the wrong size");
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
  const RealFft2d kernel_fft(N1, N2, N2);  // the kernels fill every row
  const auto scaled = [normalisation](double value) { return value * normalisation; };
  for (int k = 0; k < components; ++k) {
    for (int l = 0; l < components; ++l) {
      FftwArray<std::complex<double>>& spectrum = kernel_spectra_[static_cast<std::size_t>(k * components + l)];
      spectrum = FftwArray<std::complex<double>>(fft_.spectrum_size());
      if (symmetric_blocks && l < k) {  // K_kl = K_lk: already transformed
        const auto& same = kernel_spectra_[static_cast<std::size_t>(l * components + k)];
        std::copy_n(same.data(), same.size(), spectrum.data());
        continue;
      }
      std::fill(real, real + fft_.real_size(), 0.0);
      // Offset m is stored at m mod N (wrap-around order): per table row, the offsets m1 >= 0 at
      // the start of the transform row, m1 < 0 at its end.
      const double* block = kernel_table.data() + static_cast<std::size_t>(k * components + l) * w1 * w2;
      for (int m2 = -(n2 - 1); m2 <= n2 - 1; ++m2) {
        const double* row = block + static_cast<std::size_t>(m2 + n2 - 1) * w1;  // m1 = -(n1-1) first
        double* out = real + static_cast<std::size_t>(m2 < 0 ? m2 + N2 : m2) * N1;
        std::transform(row + (n1 - 1), row + w1, out, scaled);
        std::transform(row, row + (n1 - 1), out + (N1 - (n1 - 1)), scaled);
      }
      kernel_fft.forward(real, spectrum.data());
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
