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
  Plans(int size1, int size2, int planned_rows)
      : n1(size1), n2(size2), rows(planned_rows), inverse_by_forward(size1 * size2 <= kInverseByForwardUpTo) {
    // Planned on scratch arrays (FFTW_ESTIMATE does not touch them), executed on others of the
    // same size and alignment. FFTW's row-major layout: n2 rows of n1 contiguous values; the half
    // spectrum between the passes has n2 rows of h = n1 / 2 + 1, the spectrum h columns of n2.
    const int h = n1 / 2 + 1;
    FftwArray<double> real(static_cast<std::size_t>(n1) * n2);
    FftwArray<std::complex<double>> half_rows(static_cast<std::size_t>(n2) * h);
    FftwArray<std::complex<double>> columns(static_cast<std::size_t>(n2) * h);
    auto* rows_data = reinterpret_cast<fftw_complex*>(half_rows.data());
    auto* columns_data = reinterpret_cast<fftw_complex*>(columns.data());
    const int length1[] = {n1};
    const int length2[] = {n2};
    // Along x1: the rows that can be non-zero (forward) or are wanted (inverse).
    forward =
        fftw_plan_many_dft_r2c(1, length1, rows, real.data(), nullptr, 1, n1, rows_data, nullptr, 1, h, FFTW_ESTIMATE);
    if (!inverse_by_forward)
      inverse =
          fftw_plan_many_dft_c2r(1, length1, rows, rows_data, nullptr, 1, h, real.data(), nullptr, 1, n1, FFTW_ESTIMATE);
    // Along x2: every column, from the strided rows to contiguous columns and back.
    forward_columns = fftw_plan_many_dft(1, length2, h, rows_data, nullptr, h, 1, columns_data, nullptr, 1, n2,
                                         FFTW_FORWARD, FFTW_ESTIMATE);
    inverse_columns = fftw_plan_many_dft(1, length2, h, columns_data, nullptr, 1, n2, rows_data, nullptr, h, 1,
                                         FFTW_BACKWARD, FFTW_ESTIMATE);
    check(forward != nullptr && forward_columns != nullptr && inverse_columns != nullptr &&
          (inverse_by_forward || inverse != nullptr));
    estimated_cost = fftw_estimate_cost(forward) + fftw_estimate_cost(forward_columns) +
                     fftw_estimate_cost(inverse_columns) + fftw_estimate_cost(inverse_by_forward ? forward : inverse);
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
  // Transforms of up to this many points compute the inverse along x1 with the forward plan
  // (RealFft2d::inverse): FFTW plans a real transform of length 42 in ~0.1 ms, most of a small
  // convolution's first use in a process, while the extra passes cost ~0.3 µs per inverse
  // (docs/FFT.md "The inverse of small transforms through the forward plan").
  static constexpr int kInverseByForwardUpTo = 64 * 64;
  int n1, n2, rows;
  bool inverse_by_forward;
  double estimated_cost = 0.0;  // FFTW's own estimate of a forward + inverse pair (deterministic)
  fftw_plan forward = nullptr;          // r2c along x1 on the first `rows` rows
  fftw_plan forward_columns = nullptr;  // c2c along x2, every column: strided rows -> contiguous columns
  fftw_plan inverse_columns = nullptr;  // its inverse: contiguous columns -> strided rows
  fftw_plan inverse = nullptr;          // c2r along x1 on the first `rows` rows (not made if inverse_by_forward)
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
  constexpr std::size_t kKeptSizes = 64;
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

// Whether a convolution of an n1 x n2 grid transforms its rows along x2 (x2 contiguous in the
// padded arrays) rather than along x1: the layout of the two whose plans FFTW estimates cheaper.
// The same work in flops, but FFTW_ESTIMATE's plans for the strided column transforms differ with
// the length along the columns (measured: docs/FFT.md "Which axis the rows run along"). FFTW's estimate is a deterministic
// function of the sizes, so a size always gets the same layout (no timing enters a result).
// Transforms of at most kInverseByForwardUpTo points keep rows along x1: their planning is most
// of a small convolution's first use (docs/FFT.md), and a second layout would plan twice.
bool transform_rows_along_x2(int n1, int n2) {
  const int N1 = fft_friendly_length(2 * n1 - 1), N2 = fft_friendly_length(2 * n2 - 1);
  if (N1 * N2 <= RealFft2d::Plans::kInverseByForwardUpTo || (N1 == N2 && n1 == n2)) return false;
  struct Decision {
    int n1, n2;
    bool rows_along_x2;
  };
  constexpr std::size_t kKeptDecisions = 64;
  thread_local std::vector<Decision> decided;
  for (const Decision& d : decided)
    if (d.n1 == n1 && d.n2 == n2) return d.rows_along_x2;
  const double along_x1 = plans_for(N1, N2, n2)->estimated_cost;
  const double along_x2 = plans_for(N2, N1, n1)->estimated_cost;
  if (decided.size() == kKeptDecisions) decided.erase(decided.begin());
  decided.push_back({n1, n2, along_x2 < along_x1});
  return decided.back().rows_along_x2;
}

}  // namespace

RealFft2d::RealFft2d(int n1, int n2, int rows) : n1_(n1), n2_(n2), rows_(rows) {
  require(n1 > 0 && n2 > 0 && rows > 0 && rows <= n2, "FFT: invalid transform size");
  plans_ = plans_for(n1, n2, rows);
  forward_rows_ = FftwArray<std::complex<double>>(spectrum_size());  // zero-filled
  inverse_rows_ = FftwArray<std::complex<double>>(spectrum_size());
  if (plans_->inverse_by_forward) hartley_rows_ = FftwArray<double>(real_size());
}

RealFft2d::RealFft2d(const RealFft2d& same, SharePlans)
    : n1_(same.n1_), n2_(same.n2_), rows_(same.rows_), plans_(same.plans_) {
  forward_rows_ = FftwArray<std::complex<double>>(spectrum_size());  // zero-filled
  inverse_rows_ = FftwArray<std::complex<double>>(spectrum_size());
  if (plans_->inverse_by_forward) hartley_rows_ = FftwArray<double>(real_size());
}

void RealFft2d::forward(const double* real, std::complex<double>* spectrum) {
  // FFTW's r2c transforms leave their input intact (no FFTW_DESTROY_INPUT for r2c); the rows past
  // `rows` of forward_rows_ are never written and stay zero (the padding rows' transforms).
  auto* rows = reinterpret_cast<fftw_complex*>(forward_rows_.data());
  fftw_execute_dft_r2c(plans_->forward, const_cast<double*>(real), rows);
  // Out-of-place c2c keeps its input (FFTW_PRESERVE_INPUT is the default but for c2r).
  fftw_execute_dft(plans_->forward_columns, rows, reinterpret_cast<fftw_complex*>(spectrum));
}

void RealFft2d::inverse(const std::complex<double>* spectrum, double* real) {
  auto* rows = reinterpret_cast<fftw_complex*>(inverse_rows_.data());
  fftw_execute_dft(plans_->inverse_columns, reinterpret_cast<fftw_complex*>(const_cast<std::complex<double>*>(spectrum)),
                   rows);
  if (plans_->inverse_by_forward) {
    inverse_rows_through_forward(real);
    return;
  }
  fftw_execute_dft_c2r(plans_->inverse, rows, real);  // destroys rows, which is scratch
}

void RealFft2d::inverse_rows_through_forward(double* real) {
  // The unnormalised real inverse of a Hermitian row Y (Y[N - k] = conj Y[k], N = n1_),
  //   y[n] = sum_k Y[k] e^(+2 pi i k n / N) = sum_k (A[k] cos - B[k] sin)(2 pi k n / N),
  // with A = Re Y even and B = Im Y odd in k, from the forward real transform W of the real row
  // s = A + B: Re W[n] = sum_k A[k] cos (B odd drops out) and Im W[n] = -sum_k B[k] sin (A even
  // drops out), so y[n] = Re W[n] + Im W[n] (Hartley's cas = cos + sin, read backwards). Like
  // FFTW's c2r, the imaginary parts of Y[0] and Y[N/2] (zero for a Hermitian row) are ignored.
  const auto N = static_cast<std::size_t>(n1_);
  const std::size_t h = N / 2 + 1;
  const auto* Y = reinterpret_cast<const double*>(inverse_rows_.data());  // (re, im) pairs, h per row
  double* s = hartley_rows_.data();
  for (std::size_t r = 0; r < static_cast<std::size_t>(rows_); ++r) {
    const double* y_row = Y + 2 * h * r;
    double* s_row = s + N * r;
    for (std::size_t k = 0; k < h; ++k) s_row[k] = y_row[2 * k] + y_row[2 * k + 1];
    for (std::size_t k = h; k < N; ++k) s_row[k] = y_row[2 * (N - k)] - y_row[2 * (N - k) + 1];
    s_row[0] = y_row[0];
    if (N % 2 == 0) s_row[N / 2] = y_row[N];
  }
  // W into the half rows, which are read.
  fftw_execute_dft_r2c(plans_->forward, s, reinterpret_cast<fftw_complex*>(inverse_rows_.data()));
  const auto* W = reinterpret_cast<const double*>(inverse_rows_.data());
  for (std::size_t r = 0; r < static_cast<std::size_t>(rows_); ++r) {
    const double* w_row = W + 2 * h * r;
    double* out = real + N * r;
    for (std::size_t n = 0; n < h; ++n) out[n] = w_row[2 * n] + w_row[2 * n + 1];
  }
}

void RealFft2d::forward_wrapped(const double* real, std::complex<double>* spectrum) const {
  // New-array execution of the row plan on arrays of the planned size and (fftw_malloc) alignment.
  const auto h = static_cast<std::size_t>(n1_ / 2 + 1);
  const auto n1 = static_cast<std::size_t>(n1_);
  const auto rows = static_cast<std::size_t>(rows_);
  FftwArray<std::complex<double>> half_rows(spectrum_size());  // zero-filled: the zero rows' transforms
  fftw_execute_dft_r2c(plans_->forward, const_cast<double*>(real), reinterpret_cast<fftw_complex*>(half_rows.data()));
  const std::size_t last = static_cast<std::size_t>(n2_) - rows;  // the first of the last `rows` rows
  if (last > 0) {
    FftwArray<double> moved(real_size());
    std::copy_n(real + last * n1, rows * n1, moved.data());
    FftwArray<std::complex<double>> moved_rows(spectrum_size());
    fftw_execute_dft_r2c(plans_->forward, moved.data(), reinterpret_cast<fftw_complex*>(moved_rows.data()));
    std::copy_n(moved_rows.data(), rows * h, half_rows.data() + last * h);  // overlapping rows: equal
  }
  fftw_execute_dft(plans_->forward_columns, reinterpret_cast<fftw_complex*>(half_rows.data()),
                   reinterpret_cast<fftw_complex*>(spectrum));
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
  // inverse, half the rows non-zero, as in every convolution here; RealFft2d's column-by-column
  // spectrum) are faster than at every longer length: the cheapest choice for any minimum up to
  // 512 (measured on square transforms, docs/DEPENDENCIES.md "Padded lengths"). The smallest
  // 7-smooth length was up to 3x slower (54 against 56, 60 against 64, 126 against 128). 36 and 40,
  // faster than 42 there, are left out: FFTW plans them in 0.42 and 0.9 ms against 0.22 ms, which
  // was half of nH-FastSim's first solve in a process (its coarse K2 transforms along the rolling
  // direction at 36 to 42), and with the 32 across of its coarse patch 36 and 42 transform equally
  // fast (docs/BENCHMARKS.md, issue #15).
  static constexpr int kFastLengths[] = {16,  20,  32,  42,  48,  50,  56,  64,  72,  80,  84,  100, 112,
                                         120, 128, 140, 144, 160, 200, 224, 256, 320, 336, 384, 400, 448, 512};
  if (minimum <= 16 || minimum > 512) return smooth_length(minimum);
  return *std::lower_bound(std::begin(kFastLengths), std::end(kFastLengths), minimum);
}

RealFft2d FftConvolution::make_transform(int n1, int n2, bool rows_along_x2) {
  const int N1 = fft_friendly_length(2 * n1 - 1), N2 = fft_friendly_length(2 * n2 - 1);
  return rows_along_x2 ? RealFft2d(N2, N1, n1) : RealFft2d(N1, N2, n2);
}

FftConvolution::FftConvolution(int n1, int n2, int components, std::span<const double> kernel_table,
                               bool symmetric_blocks)
    : n1_(n1),
      n2_(n2),
      components_(components),
      rows_along_x2_(transform_rows_along_x2(n1, n2)),
      fft_(make_transform(n1, n2, rows_along_x2_)),
      sum_(fft_.spectrum_size()) {
  const std::size_t w1 = static_cast<std::size_t>(2 * n1 - 1);
  const std::size_t w2 = static_cast<std::size_t>(2 * n2 - 1);
  require(kernel_table.size() == static_cast<std::size_t>(components * components) * w1 * w2,
          "FFT convolution: kernel table of the wrong size");
  const int N1 = rows_along_x2_ ? fft_.n2() : fft_.n1();  // padded lengths along x1 and x2
  const int N2 = rows_along_x2_ ? fft_.n1() : fft_.n2();
  const double normalisation = 1.0 / (static_cast<double>(N1) * N2);
  allocate_buffers();
  auto spectra = std::make_shared<KernelSpectra>(static_cast<std::size_t>(components * components));
  double* real = outputs_[0].data();  // scratch until the first product
  const auto scaled = [normalisation](double value) { return value * normalisation; };
  for (int k = 0; k < components; ++k) {
    for (int l = 0; l < components; ++l) {
      FftwArray<std::complex<double>>& spectrum = (*spectra)[static_cast<std::size_t>(k * components + l)];
      spectrum = FftwArray<std::complex<double>>(fft_.spectrum_size());
      if (symmetric_blocks && l < k) {  // K_kl = K_lk: already transformed
        const auto& same = (*spectra)[static_cast<std::size_t>(l * components + k)];
        std::copy_n(same.data(), same.size(), spectrum.data());
        continue;
      }
      std::fill(real, real + fft_.real_size(), 0.0);
      // Offset m is stored at m mod N (wrap-around order): per table row, the offsets m1 >= 0 at
      // the start of the transform row, m1 < 0 at its end.
      const double* block = kernel_table.data() + static_cast<std::size_t>(k * components + l) * w1 * w2;
      for (int m2 = -(n2 - 1); m2 <= n2 - 1; ++m2) {
        const double* row = block + static_cast<std::size_t>(m2 + n2 - 1) * w1;  // m1 = -(n1-1) first
        const int wrapped2 = m2 < 0 ? m2 + N2 : m2;
        if (!rows_along_x2_) {
          double* out = real + static_cast<std::size_t>(wrapped2) * N1;
          std::transform(row + (n1 - 1), row + w1, out, scaled);
          std::transform(row, row + (n1 - 1), out + (N1 - (n1 - 1)), scaled);
          continue;
        }
        for (int m1 = -(n1 - 1); m1 <= n1 - 1; ++m1)
          real[static_cast<std::size_t>(m1 < 0 ? m1 + N1 : m1) * N2 + wrapped2] = scaled(row[m1 + n1 - 1]);
      }
      fft_.forward_wrapped(real, spectrum.data());  // the transform rows past the grid's and before the last ones are zero
    }
  }
  kernel_spectra_ = std::move(spectra);
}

FftConvolution::FftConvolution(int n1, int n2, int components, std::shared_ptr<const KernelSpectra> kernel_spectra)
    : n1_(n1),
      n2_(n2),
      components_(components),
      rows_along_x2_(transform_rows_along_x2(n1, n2)),
      fft_(make_transform(n1, n2, rows_along_x2_)),
      kernel_spectra_(std::move(kernel_spectra)),
      sum_(fft_.spectrum_size()) {
  require(kernel_spectra_ != nullptr &&
              kernel_spectra_->size() == static_cast<std::size_t>(components * components) &&
              kernel_spectra_->front().size() == fft_.spectrum_size(),
          "FFT convolution: kernel spectra of the wrong size");
  allocate_buffers();
}

FftConvolution::FftConvolution(const FftConvolution& same, ShareKernels)
    : n1_(same.n1_),
      n2_(same.n2_),
      components_(same.components_),
      rows_along_x2_(same.rows_along_x2_),
      fft_(same.fft_, RealFft2d::SharePlans{}),
      kernel_spectra_(same.kernel_spectra_),
      sum_(fft_.spectrum_size()) {
  allocate_buffers();
}

void FftConvolution::allocate_buffers() {
  for (int c = 0; c < components_; ++c) {
    inputs_.emplace_back(fft_.real_size());
    outputs_.emplace_back(fft_.real_size());
    input_spectra_.emplace_back(fft_.spectrum_size());
  }
}

void FftConvolution::clear_inputs() {
  // The grid's rows of the transform (along x1 or x2) and their elements.
  const auto stride = static_cast<std::size_t>(fft_.n1());
  const int rows = rows_along_x2_ ? n1_ : n2_, length = rows_along_x2_ ? n2_ : n1_;
  for (FftwArray<double>& in : inputs_)
    for (int r = 0; r < rows; ++r) std::fill_n(in.data() + static_cast<std::size_t>(r) * stride, length, 0.0);
}

namespace {

// out = K P (accumulate: out += K P) on interleaved (re, im) spectra of `count` values; conjugate:
// K's conjugate (the transposed kernel's spectrum). Written out on (re, im) pairs: std::complex's
// operator* guards against NaN (C99 Annex G) and does not vectorise. One loop per case, without a
// branch inside, so that the compiler vectorises it.
template <bool kAccumulate, bool kConjugate>
void multiply_spectra(const double* __restrict K, const double* __restrict P, double* __restrict out,
                      std::size_t count) {
  for (std::size_t q = 0; q < 2 * count; q += 2) {
    const double kr = K[q], ki = kConjugate ? -K[q + 1] : K[q + 1], pr = P[q], pi = P[q + 1];
    const double re = kr * pr - ki * pi, im = kr * pi + ki * pr;
    if constexpr (kAccumulate) {
      out[q] += re;
      out[q + 1] += im;
    } else {
      out[q] = re;
      out[q + 1] = im;
    }
  }
}

}  // namespace

void FftConvolution::convolve(bool transpose) {
  for (int l = 0; l < components_; ++l)
    fft_.forward(inputs_[static_cast<std::size_t>(l)].data(), input_spectra_[static_cast<std::size_t>(l)].data());
  const std::size_t ns = fft_.spectrum_size();
  double* acc = reinterpret_cast<double*>(sum_.data());
  for (int k = 0; k < components_; ++k) {
    for (int l = 0; l < components_; ++l) {
      const auto* K = reinterpret_cast<const double*>(
          (*kernel_spectra_)[static_cast<std::size_t>(transpose ? l * components_ + k : k * components_ + l)].data());
      const auto* P = reinterpret_cast<const double*>(input_spectra_[static_cast<std::size_t>(l)].data());
      if (l == 0) {
        transpose ? multiply_spectra<false, true>(K, P, acc, ns) : multiply_spectra<false, false>(K, P, acc, ns);
      } else {
        transpose ? multiply_spectra<true, true>(K, P, acc, ns) : multiply_spectra<true, false>(K, P, acc, ns);
      }
    }
    fft_.inverse(sum_.data(), outputs_[static_cast<std::size_t>(k)].data());
  }
}

void FftConvolution::apply(std::span<const double> in, std::span<double> out) {
  const std::size_t n = grid_size();
  require(in.size() == n * components_ && out.size() == n * components_, "FFT convolution: wrong field size");
  const auto stride = static_cast<std::size_t>(fft_.n1());
  const auto n1 = static_cast<std::size_t>(n1_);
  for (int c = 0; c < components_; ++c) {
    const double* field = in.data() + static_cast<std::size_t>(c) * n;
    double* padded = input(c);
    for (std::size_t i2 = 0; i2 < static_cast<std::size_t>(n2_); ++i2) {
      if (rows_along_x2_) {
        for (std::size_t i1 = 0; i1 < n1; ++i1) padded[i1 * stride + i2] = field[i2 * n1 + i1];
      } else {
        std::copy_n(field + i2 * n1, n1, padded + i2 * stride);
      }
    }
  }
  convolve(false);
  for (int c = 0; c < components_; ++c) {
    double* field = out.data() + static_cast<std::size_t>(c) * n;
    const double* padded = output(c);
    for (std::size_t i2 = 0; i2 < static_cast<std::size_t>(n2_); ++i2) {
      if (rows_along_x2_) {
        for (std::size_t i1 = 0; i1 < n1; ++i1) field[i2 * n1 + i1] = padded[i1 * stride + i2];
      } else {
        std::copy_n(padded + i2 * stride, n1, field + i2 * n1);
      }
    }
  }
}

}  // namespace railcontact::detail
