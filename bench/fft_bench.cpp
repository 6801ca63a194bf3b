// The FFT library choice (docs/FFT.md): FFTW3 against Eigen's FFT module (KissFFT backend, the
// only double-precision KissFFT on Debian 12: libkissfft-dev ships single precision only),
// for the zero-padded 2-D real transforms of the influence operators.
#include <benchmark/benchmark.h>
#include <fftw3.h>

#include "elastic/fft_convolution.hpp"

#include <complex>
#include <unsupported/Eigen/FFT>
#include <vector>

namespace {

void BM_Fftw_RealForward2d(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  double* in = fftw_alloc_real(static_cast<std::size_t>(n) * n);
  fftw_complex* out = fftw_alloc_complex(static_cast<std::size_t>(n) * (n / 2 + 1));
  fftw_plan plan = fftw_plan_dft_r2c_2d(n, n, in, out, FFTW_ESTIMATE);
  for (int k = 0; k < n * n; ++k) in[k] = (k % 7) * 0.1;
  for (auto _ : state) {
    fftw_execute(plan);
    benchmark::DoNotOptimize(out);
  }
  fftw_destroy_plan(plan);
  fftw_free(in);
  fftw_free(out);
}
BENCHMARK(BM_Fftw_RealForward2d)->Arg(120)->Arg(240)->Unit(benchmark::kMicrosecond);

void BM_EigenKissFft_RealForward2d(benchmark::State& state) {
  // Row transforms (real, half spectrum) then column transforms (complex).
  const int n = static_cast<int>(state.range(0));
  const int h = n / 2 + 1;
  Eigen::FFT<double> fft;
  fft.SetFlag(Eigen::FFT<double>::HalfSpectrum);
  std::vector<double> row(static_cast<std::size_t>(n));
  std::vector<std::complex<double>> spectrum(static_cast<std::size_t>(n) * h), row_out, column(n), column_out;
  std::vector<double> in(static_cast<std::size_t>(n) * n);
  for (int k = 0; k < n * n; ++k) in[k] = (k % 7) * 0.1;
  for (auto _ : state) {
    for (int r = 0; r < n; ++r) {
      row.assign(in.begin() + static_cast<std::ptrdiff_t>(r) * n, in.begin() + static_cast<std::ptrdiff_t>(r + 1) * n);
      fft.fwd(row_out, row);
      for (int c = 0; c < h; ++c) spectrum[static_cast<std::size_t>(r) * h + c] = row_out[c];
    }
    for (int c = 0; c < h; ++c) {
      for (int r = 0; r < n; ++r) column[r] = spectrum[static_cast<std::size_t>(r) * h + c];
      fft.fwd(column_out, column);
      for (int r = 0; r < n; ++r) spectrum[static_cast<std::size_t>(r) * h + c] = column_out[r];
    }
    benchmark::DoNotOptimize(spectrum.data());
  }
}
BENCHMARK(BM_EigenKissFft_RealForward2d)->Arg(120)->Arg(240)->Unit(benchmark::kMicrosecond);

// Padded lengths and pruning (docs/DEPENDENCIES.md): forward + inverse square transform as a
// convolution uses it (RealFft2d's rows: only the first (minimum + 1) / 2 rows are non-zero on
// input and wanted on output), for minimum lengths 2n - 1 of meshes with n = 18, 24, 30, 36, 42,
// 48, 54, 60, 66, 72 elements per axis: at the smallest 7-smooth length >= the minimum, at the
// measured fast length, and at the fast length without pruning (every row transformed).
void fft_round_trip(benchmark::State& state, int n, int rows) {
  railcontact::detail::RealFft2d fft(n, n, rows);
  railcontact::detail::FftwArray<double> real(fft.real_size());
  railcontact::detail::FftwArray<std::complex<double>> spectrum(fft.spectrum_size());
  for (int k = 0; k < rows * n; ++k) real.data()[k] = (k % 7) * 0.1;
  for (auto _ : state) {
    fft.forward(real.data(), spectrum.data());
    fft.inverse(spectrum.data(), real.data());
    benchmark::DoNotOptimize(real.data());
  }
  state.counters["length"] = n;
}
int grid_rows(const benchmark::State& state) { return (static_cast<int>(state.range(0)) + 1) / 2; }
void BM_FftRoundTrip_SmoothLength(benchmark::State& state) {
  fft_round_trip(state, railcontact::detail::smooth_length(static_cast<int>(state.range(0))), grid_rows(state));
}
void BM_FftRoundTrip_FastLength(benchmark::State& state) {
  fft_round_trip(state, railcontact::detail::fft_friendly_length(static_cast<int>(state.range(0))), grid_rows(state));
}
void BM_FftRoundTrip_FastLengthUnpruned(benchmark::State& state) {
  const int n = railcontact::detail::fft_friendly_length(static_cast<int>(state.range(0)));
  fft_round_trip(state, n, n);
}
BENCHMARK(BM_FftRoundTrip_SmoothLength)->DenseRange(35, 143, 12)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_FftRoundTrip_FastLength)->DenseRange(35, 143, 12)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_FftRoundTrip_FastLengthUnpruned)->DenseRange(35, 143, 12)->Unit(benchmark::kMicrosecond);

// Which axis the rows run along (docs/FFT.md "Which axis the rows run along"): a convolution's
// forward + inverse pair on an n1 x n2 grid (the arguments) with the rows along x1 (transform N1 x
// N2, n2 rows non-zero) and along x2 (N2 x N1, n1 rows), and the convolution's own product
// (FftConvolution::apply, counter rows_along_x2: the layout it chose). The grids are the
// wheelset time step's: its contact windows at y = 0 (60 x 112, 64 x 112) and in flange contact
// (224 x 20, 80 x 60, 240 x 72), and the whole potential area at y = 0 (96 x 144).
void rows_along(benchmark::State& state, bool along_x2) {
  const int n1 = static_cast<int>(state.range(0)), n2 = static_cast<int>(state.range(1));
  const int N1 = railcontact::detail::fft_friendly_length(2 * n1 - 1);
  const int N2 = railcontact::detail::fft_friendly_length(2 * n2 - 1);
  railcontact::detail::RealFft2d fft = along_x2 ? railcontact::detail::RealFft2d(N2, N1, n1)
                                                : railcontact::detail::RealFft2d(N1, N2, n2);
  railcontact::detail::FftwArray<double> real(fft.real_size());
  railcontact::detail::FftwArray<std::complex<double>> spectrum(fft.spectrum_size());
  for (int k = 0; k < (along_x2 ? n1 * N2 : n2 * N1); ++k) real.data()[k] = (k % 7) * 0.1;
  for (auto _ : state) {
    fft.forward(real.data(), spectrum.data());
    fft.inverse(spectrum.data(), real.data());
    benchmark::DoNotOptimize(real.data());
  }
}
void BM_FftRoundTrip_RowsAlongX1(benchmark::State& state) { rows_along(state, false); }
void BM_FftRoundTrip_RowsAlongX2(benchmark::State& state) { rows_along(state, true); }
void BM_FftConvolution_Apply(benchmark::State& state) {
  const int n1 = static_cast<int>(state.range(0)), n2 = static_cast<int>(state.range(1));
  const std::vector<double> kernel(static_cast<std::size_t>(2 * n1 - 1) * static_cast<std::size_t>(2 * n2 - 1), 1.0);
  railcontact::detail::FftConvolution convolution(n1, n2, 1, kernel);
  std::vector<double> in(static_cast<std::size_t>(n1) * static_cast<std::size_t>(n2), 1.0), out(in.size());
  for (auto _ : state) {
    convolution.apply(in, out);
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["rows_along_x2"] = convolution.rows_along_x2();
}
#define RAILCONTACT_WINDOW_GRIDS                                                                            \
  ->Args({60, 112})->Args({64, 112})->Args({96, 144})->Args({224, 20})->Args({80, 60})->Args({240, 72}) \
      ->Unit(benchmark::kMicrosecond)
BENCHMARK(BM_FftRoundTrip_RowsAlongX1) RAILCONTACT_WINDOW_GRIDS;
BENCHMARK(BM_FftRoundTrip_RowsAlongX2) RAILCONTACT_WINDOW_GRIDS;
BENCHMARK(BM_FftConvolution_Apply) RAILCONTACT_WINDOW_GRIDS;

}  // namespace

BENCHMARK_MAIN();
