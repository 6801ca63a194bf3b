// Influence coefficients and operators against independent references: polar-coordinate
// quadrature (exact treatment of the 1/r singularity), Gauss quadrature away from the element,
// the textbook centre displacement of a uniformly loaded square, and the dense matrix.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "elastic/fft_convolution.hpp"
#include "elastic/influence_operator.hpp"
#include "elastic/influence_coefficients.hpp"

namespace railcontact {
namespace {

const Material kSteel{2.1e11, 0.3};

// P_n(z) and P_n'(z) by the three-term recurrence.
struct Legendre {
  double value, derivative;
};
Legendre legendre(int n, double z) {
  double p0 = 1, p1 = z;
  for (int k = 2; k <= n; ++k) {
    const double p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
    p0 = p1;
    p1 = p2;
  }
  return {p1, n * (z * p1 - p0) / (z * z - 1)};
}

// Gauss-Legendre nodes/weights on [-1, 1] (Golub-Welsch-free: Newton on P_n).
void gauss_legendre(int n, std::vector<double>& x, std::vector<double>& w) {
  x.resize(n);
  w.resize(n);
  for (int i = 0; i < n; ++i) {
    double z = std::cos(M_PI * (i + 0.75) / (n + 0.5));
    for (int it = 0; it < 100; ++it) {
      const Legendre p = legendre(n, z);
      const double dz = p.value / p.derivative;
      z -= dz;
      if (std::fabs(dz) < 1e-16) break;
    }
    const double dp = legendre(n, z).derivative;
    x[i] = z;
    w[i] = 2 / ((1 - z * z) * dp * dp);
  }
}

// ∫∫ over the rectangle [-h1,h1]x[-h2,h2] of g(theta)/r dA seen from an interior point (x, y):
// in polar coordinates = ∫ g(theta) R(theta) dtheta, R = distance to the boundary.
// Integrated piecewise between the corner directions (R is smooth there).
double polar_integral(double x, double y, double h1, double h2, double (*g)(double)) {
  auto R = [&](double t) {
    const double c = std::cos(t), s = std::sin(t);
    double r = 1e300;
    if (c > 1e-300) r = std::min(r, (h1 - x) / c);
    if (c < -1e-300) r = std::min(r, (-h1 - x) / c);
    if (s > 1e-300) r = std::min(r, (h2 - y) / s);
    if (s < -1e-300) r = std::min(r, (-h2 - y) / s);
    return r;
  };
  std::vector<double> angles = {std::atan2(h2 - y, h1 - x), std::atan2(h2 - y, -h1 - x), std::atan2(-h2 - y, -h1 - x),
                                std::atan2(-h2 - y, h1 - x)};
  for (double& a : angles)
    if (a < 0) a += 2 * M_PI;
  std::sort(angles.begin(), angles.end());
  angles.push_back(angles.front() + 2 * M_PI);
  std::vector<double> gx, gw;
  gauss_legendre(40, gx, gw);
  double total = 0;
  const int pieces = 64;  // R is smooth but steep near an edge: composite rule
  for (std::size_t k = 0; k + 1 < angles.size(); ++k) {
    for (int piece = 0; piece < pieces; ++piece) {
      const double a = angles[k] + (angles[k + 1] - angles[k]) * piece / pieces;
      const double b = angles[k] + (angles[k + 1] - angles[k]) * (piece + 1) / pieces;
      for (std::size_t q = 0; q < gx.size(); ++q) {
        const double t = 0.5 * (a + b) + 0.5 * (b - a) * gx[q];
        total += 0.5 * (b - a) * gw[q] * g(t) * R(t);
      }
    }
  }
  return total;
}

double g_one(double) { return 1.0; }
double g_cos2(double t) { return std::cos(t) * std::cos(t); }
double g_sin2(double t) { return std::sin(t) * std::sin(t); }
double g_cossin(double t) { return std::cos(t) * std::sin(t); }

TEST(InfluenceCoefficients, CentreOfUniformlyLoadedSquareMatchesTextbook) {
  // Johnson, Contact Mechanics §3.9: ∫∫ dA / r over a square of side 2c at its centre = 8 c ln(1 + sqrt 2).
  const double c = 1e-3;
  const double expected = (1 - kSteel.poisson_ratio) / (M_PI * kSteel.shear_modulus_Pa()) * 8 * c * std::log(1 + std::sqrt(2.0));
  EXPECT_NEAR(normal_influence(0, 0, {2 * c, 2 * c}, kSteel), expected, 1e-14 * expected);
}

TEST(InfluenceCoefficients, InteriorPointsMatchPolarQuadrature) {
  const double h1 = 0.7e-3, h2 = 0.4e-3;
  const ElementSize element{2 * h1, 2 * h2};
  const double nu = kSteel.poisson_ratio, scale = 1 / (M_PI * kSteel.shear_modulus_Pa());
  for (auto [x, y] : {std::pair{0.0, 0.0}, {0.3e-3, -0.1e-3}, {-0.69e-3, 0.35e-3}, {0.35e-3, 0.0}}) {
    const double one = polar_integral(x, y, h1, h2, g_one);
    const double a33 = (1 - nu) * scale * one;
    EXPECT_NEAR(normal_influence(x, y, element, kSteel), a33, 1e-10 * a33);
    const TangentialInfluence t = tangential_influence(x, y, element, kSteel);
    const double a11 = scale * ((1 - nu) * one + nu * polar_integral(x, y, h1, h2, g_cos2));
    const double a22 = scale * ((1 - nu) * one + nu * polar_integral(x, y, h1, h2, g_sin2));
    const double a12 = scale * nu * polar_integral(x, y, h1, h2, g_cossin);
    EXPECT_NEAR(t.a11, a11, 1e-10 * a11);
    EXPECT_NEAR(t.a22, a22, 1e-10 * a22);
    EXPECT_NEAR(t.a12, a12, 1e-10 * a11);
  }
}

TEST(InfluenceCoefficients, DistantPointsMatchGaussQuadratureOfPointForceKernels) {
  const double h1 = 0.5e-3, h2 = 0.8e-3;
  const ElementSize element{2 * h1, 2 * h2};
  const double nu = kSteel.poisson_ratio, scale = 1 / (M_PI * kSteel.shear_modulus_Pa());
  std::vector<double> gx, gw;
  gauss_legendre(30, gx, gw);
  for (auto [x, y] : {std::pair{3e-3, 1e-3}, {-2e-3, -2.5e-3}, {0.0, 4e-3}}) {
    double one = 0, xx = 0, yy = 0, xy = 0;
    for (std::size_t i = 0; i < gx.size(); ++i)
      for (std::size_t j = 0; j < gx.size(); ++j) {
        const double X = x - h1 * gx[i], Y = y - h2 * gx[j];
        const double r = std::hypot(X, Y), w = gw[i] * gw[j] * h1 * h2;
        one += w / r;
        xx += w * X * X / (r * r * r);
        yy += w * Y * Y / (r * r * r);
        xy += w * X * Y / (r * r * r);
      }
    EXPECT_NEAR(normal_influence(x, y, element, kSteel), (1 - nu) * scale * one, 1e-11 * scale * one);
    const TangentialInfluence t = tangential_influence(x, y, element, kSteel);
    EXPECT_NEAR(t.a11, scale * ((1 - nu) * one + nu * xx), 1e-11 * scale * one);
    EXPECT_NEAR(t.a22, scale * ((1 - nu) * one + nu * yy), 1e-11 * scale * one);
    EXPECT_NEAR(t.a12, scale * nu * xy, 1e-11 * scale * one);
  }
}

TEST(InfluenceCoefficients, SymmetriesOfTheKernels) {
  const ElementSize element{1e-3, 2e-3};
  const TangentialInfluence a = tangential_influence(1.7e-3, 2.3e-3, element, kSteel);
  const TangentialInfluence b = tangential_influence(-1.7e-3, 2.3e-3, element, kSteel);
  EXPECT_DOUBLE_EQ(a.a11, b.a11);
  EXPECT_DOUBLE_EQ(a.a12, -b.a12);
  EXPECT_GT(a.a12, 0.0);  // nu x y / r^3 > 0 in the first quadrant
}

// Random tractions on an irregular set of elements: FFT product equals the dense product.
void expect_fft_equals_dense(InfluenceOperator& op, unsigned seed) {
  const Mesh& mesh = op.mesh();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  std::vector<std::size_t> elements;
  for (std::size_t k = 0; k < mesh.size(); ++k)
    if (uniform(rng) > -0.3) elements.push_back(k);  // ~65% of the elements, scattered
  const std::size_t n = elements.size() * op.components();
  Eigen::VectorXd x(n);
  for (auto& v : x) v = uniform(rng) * 1e9;
  Eigen::VectorXd y_fft(n);
  op.apply(elements, {x.data(), n}, {y_fft.data(), n});
  const Eigen::MatrixXd dense = op.dense(elements);
  const Eigen::VectorXd y_dense = dense * x;
  EXPECT_LT((y_fft - y_dense).norm(), 1e-12 * y_dense.norm());
  EXPECT_LT((y_fft - y_dense).cwiseAbs().maxCoeff(), 1e-11 * y_dense.cwiseAbs().maxCoeff());
  // The adjoint product (conjugate spectra) against the transposed dense matrix.
  Eigen::VectorXd yt_fft(n);
  op.apply_transpose(elements, {x.data(), n}, {yt_fft.data(), n});
  const Eigen::VectorXd yt_dense = dense.transpose() * x;
  EXPECT_LT((yt_fft - yt_dense).norm(), 1e-12 * yt_dense.norm());
  if (op.components() == 2) EXPECT_GT((yt_dense - y_dense).norm(), 1e-3 * y_dense.norm());  // not symmetric
}

// RealFft2d computes the inverse along x1 of small transforms (at most 64 x 64 points) with its
// forward plan, of larger ones with FFTW's c2r: the 23 x 31 mesh transforms at 48 x 64 (the
// former), the 37 x 29 one at 80 x 64 (the latter), the small meshes below at odd lengths.
TEST(InfluenceOperator, FftEqualsDenseNormal) {
  const Mesh mesh = Mesh::covering(-3e-3, 3e-3, -5e-3, 4e-3, 23, 31);
  InfluenceOperator op = make_normal_operator(mesh, kSteel);
  expect_fft_equals_dense(op, 1);
}

TEST(InfluenceOperator, FftEqualsDenseSteadyRolling) {
  const Mesh mesh = Mesh::covering(-6e-3, 6e-3, -4e-3, 4e-3, 37, 29);
  for (double alpha : {0.0, 0.5, -1.0}) {
    InfluenceOperator op = make_steady_rolling_operator(mesh, kSteel, alpha);
    expect_fft_equals_dense(op, 7);
  }
}

// A convolution transforms its rows along x1 or along x2, whichever layout FFTW estimates cheaper
// for the size (FftConvolution::rows_along_x2): the 37 x 29 mesh above along x1, the 29 x 37 and
// 30 x 50 meshes here along x2 (transforms of 64 x 80 and 64 x 100). Both give the dense product.
TEST(InfluenceOperator, FftEqualsDenseWithTheTransformRowsAlongX2) {
  for (auto [n1, n2] : {std::pair{29, 37}, {30, 50}}) {
    const Mesh mesh = Mesh::covering(-4e-3, 4e-3, -6e-3, 6e-3, n1, n2);
    const std::vector<double> table((2 * n1 - 1) * (2 * n2 - 1), 1.0);
    ASSERT_TRUE(detail::FftConvolution(n1, n2, 1, table).rows_along_x2()) << n1 << " x " << n2;
    InfluenceOperator normal = make_normal_operator(mesh, kSteel);
    expect_fft_equals_dense(normal, 11);
    InfluenceOperator rolling = make_steady_rolling_operator(mesh, kSteel, 0.5);
    expect_fft_equals_dense(rolling, 13);
  }
  const std::vector<double> table((2 * 37 - 1) * (2 * 29 - 1), 1.0);
  EXPECT_FALSE(detail::FftConvolution(37, 29, 1, table).rows_along_x2());
}

// Small meshes transform at odd lengths (2 n - 1 itself when it is 7-smooth): the kernel's first and
// last rows then overlap in RealFft2d::forward_wrapped, which must still give the kernel spectra.
TEST(InfluenceOperator, FftEqualsDenseOnSmallMeshesWhereTheKernelRowsOverlap) {
  for (auto [n1, n2] : {std::pair{5, 4}, {3, 2}, {8, 8}, {2, 5}}) {
    const Mesh mesh = Mesh::covering(-2e-3, 2e-3, -1e-3, 1e-3, n1, n2);
    InfluenceOperator normal = make_normal_operator(mesh, kSteel);
    expect_fft_equals_dense(normal, 3);
    InfluenceOperator rolling = make_steady_rolling_operator(mesh, kSteel, 0.0);
    expect_fft_equals_dense(rolling, 5);
  }
}

// The kernel tables are tabulated from mirrored corner antiderivatives (odd/even in X and Y);
// every quadrant is checked against the direct per-element coefficients.
TEST(InfluenceOperator, NormalKernelMatchesDirectCoefficientsInEveryQuadrant) {
  const Mesh mesh = Mesh::covering(0, 4e-3, 0, 3e-3, 8, 6);
  InfluenceOperator op = make_normal_operator(mesh, kSteel);
  const ElementSize element{mesh.dx1_m, mesh.dx2_m};
  for (auto [m1, m2] : {std::pair{0, 0}, {-3, 2}, {5, -4}, {-7, -5}, {7, 5}, {0, -5}}) {
    const double direct = normal_influence(m1 * mesh.dx1_m, m2 * mesh.dx2_m, element, kSteel);
    EXPECT_NEAR(op.kernel(0, 0, m1, m2), direct, 1e-12 * std::fabs(direct)) << m1 << "," << m2;
  }
}

TEST(InfluenceOperator, SteadyRollingKernelIsUpwindDifferenceOfCoefficients) {
  const Mesh mesh = Mesh::covering(0, 4e-3, 0, 3e-3, 8, 6);
  for (double alpha : {0.5, 0.0}) {
  InfluenceOperator op = make_steady_rolling_operator(mesh, kSteel, alpha);
  const ElementSize element{mesh.dx1_m, mesh.dx2_m};
  for (auto [m1, m2] : {std::pair{0, 0}, {-3, 2}, {5, -4}, {-7, 0}, {-6, -5}, {7, 5}}) {
    const double x1 = (m1 + 0.5 * alpha) * mesh.dx1_m, x2 = m2 * mesh.dx2_m;
    const TangentialInfluence here = tangential_influence(x1, x2, element, kSteel);
    const TangentialInfluence ahead = tangential_influence(x1 + mesh.dx1_m, x2, element, kSteel);
    const double scale = std::fabs(here.a11) / mesh.dx1_m;
    EXPECT_NEAR(op.kernel(0, 0, m1, m2), (ahead.a11 - here.a11) / mesh.dx1_m, 1e-9 * scale);
    EXPECT_NEAR(op.kernel(0, 1, m1, m2), (ahead.a12 - here.a12) / mesh.dx1_m, 1e-9 * scale);
    EXPECT_NEAR(op.kernel(1, 1, m1, m2), (ahead.a22 - here.a22) / mesh.dx1_m, 1e-9 * scale);
    EXPECT_EQ(op.kernel(0, 1, m1, m2), op.kernel(1, 0, m1, m2));
  }
  }
}

}  // namespace
}  // namespace railcontact
