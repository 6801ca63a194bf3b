#include "elastic/influence_operator.hpp"

#include <algorithm>
#include <memory>
#include <utility>
#include <vector>

#include "elastic/rectangle_antiderivatives.hpp"
#include "railcontact/error.hpp"
#include "elastic/influence_coefficients.hpp"

namespace railcontact {
namespace {

// Influence coefficients of one element at the points (m1 + shift) dx1, m2 dx2 for
// m1 = m1_lo..m1_hi and m2 = -(n2-1)..(n2-1), sharing the corner antiderivatives between
// neighbouring offsets (one evaluation per corner instead of four per offset).
struct ElementTable {
  std::vector<double> a33, a11, a12, a22;  // (2 n2 - 1) rows of (m1_hi - m1_lo + 1), m1 fastest
};

ElementTable tabulate_element_influence(const Mesh& mesh, const Material& material, double shift, int m1_lo,
                                        int m1_hi) {
  const int c1_count = m1_hi - m1_lo + 2;  // corner columns
  const int c2_count = 2 * mesh.n2;        // corner rows, m2 - 1/2 .. m2 + 1/2
  const int m2_lo = -(mesh.n2 - 1);
  const std::size_t corners = static_cast<std::size_t>(c1_count) * c2_count;
  std::vector<double> f_one(corners), f_x2(corners), f_y2(corners), f_xy(corners);
  // The corner offsets are symmetric about 0 along X2 (Y = (c2 - n2 + 1/2) dx2), and along X1
  // too when shift = 0 (X = (c1 - n1 + 1/2) dx1 for c1 < 2 n1). Every antiderivative is odd in X
  // and in Y except -r, which is even: only the corners with Y > 0 (and X > 0 when shift = 0)
  // are evaluated, the rest mirrored bit for bit (asinh is odd).
  const bool x_mirror = shift == 0.0;
  const int c1_first = x_mirror ? mesh.n1 : 0;
  for (int c2 = mesh.n2; c2 < c2_count; ++c2) {
    const double Y = (m2_lo + c2 - 0.5) * mesh.dx2_m;
    for (int c1 = c1_first; c1 < c1_count; ++c1) {
      const double X = (m1_lo + c1 + shift - 0.5) * mesh.dx1_m;
      const RectangleAntiderivatives F = rectangle_antiderivatives(X, Y);
      const std::size_t q = static_cast<std::size_t>(c2) * c1_count + c1;
      f_one[q] = F.one_over_r;
      f_x2[q] = F.x2_over_r3;
      f_y2[q] = F.y2_over_r3;
      f_xy[q] = F.xy_over_r3;
    }
    if (x_mirror) {
      for (int c1 = 0; c1 < mesh.n1; ++c1) {
        const std::size_t q = static_cast<std::size_t>(c2) * c1_count + c1;
        const std::size_t mirror = static_cast<std::size_t>(c2) * c1_count + (2 * mesh.n1 - 1 - c1);
        f_one[q] = -f_one[mirror];
        f_x2[q] = -f_x2[mirror];
        f_y2[q] = -f_y2[mirror];
        f_xy[q] = f_xy[mirror];
      }
    }
  }
  for (int c2 = 0; c2 < mesh.n2; ++c2) {
    const std::size_t row = static_cast<std::size_t>(c2) * c1_count;
    const std::size_t mirror = static_cast<std::size_t>(c2_count - 1 - c2) * c1_count;
    for (int c1 = 0; c1 < c1_count; ++c1) {
      f_one[row + c1] = -f_one[mirror + c1];
      f_x2[row + c1] = -f_x2[mirror + c1];
      f_y2[row + c1] = -f_y2[mirror + c1];
      f_xy[row + c1] = f_xy[mirror + c1];
    }
  }
  const double nu = material.poisson_ratio;
  const double G = material.shear_modulus_Pa();
  const double normal_scale = (1.0 - nu) / (M_PI * G);
  const double tangential_scale = 1.0 / (M_PI * G);
  const std::size_t w1 = static_cast<std::size_t>(m1_hi - m1_lo + 1);
  const std::size_t w2 = static_cast<std::size_t>(2 * mesh.n2 - 1);
  ElementTable t;
  t.a33.resize(w1 * w2);
  t.a11.resize(w1 * w2);
  t.a12.resize(w1 * w2);
  t.a22.resize(w1 * w2);
  auto integral = [&](const std::vector<double>& F, std::size_t j1, std::size_t j2) {
    const std::size_t mm = j2 * c1_count + j1;  // corner (m1 - 1/2, m2 - 1/2)
    const std::size_t pm = mm + 1;
    const std::size_t mp = mm + c1_count;
    const std::size_t pp = mp + 1;
    return F[pp] - F[mp] - F[pm] + F[mm];
  };
  for (std::size_t j2 = 0; j2 < w2; ++j2) {
    for (std::size_t j1 = 0; j1 < w1; ++j1) {
      const double one = integral(f_one, j1, j2);
      const std::size_t q = j2 * w1 + j1;
      t.a33[q] = normal_scale * one;
      t.a11[q] = tangential_scale * ((1.0 - nu) * one + nu * integral(f_x2, j1, j2));
      t.a12[q] = tangential_scale * nu * integral(f_xy, j1, j2);
      t.a22[q] = tangential_scale * ((1.0 - nu) * one + nu * integral(f_y2, j1, j2));
    }
  }
  return t;
}

// K_kl = K_lk for every pair of blocks (then only half of the off-diagonal spectra are computed).
bool has_symmetric_blocks(const std::vector<double>& table, int components) {
  const std::size_t block = table.size() / static_cast<std::size_t>(components * components);
  for (int k = 0; k < components; ++k)
    for (int l = k + 1; l < components; ++l) {
      const auto kl = table.begin() + static_cast<std::ptrdiff_t>((k * components + l) * block);
      const auto lk = table.begin() + static_cast<std::ptrdiff_t>((l * components + k) * block);
      if (!std::equal(kl, kl + static_cast<std::ptrdiff_t>(block), lk)) return false;
    }
  return true;
}

}  // namespace

InfluenceOperator::InfluenceOperator(const Mesh& mesh, int components, std::vector<double> table)
    : mesh_(mesh),
      components_(components),
      table_(std::make_shared<const std::vector<double>>(std::move(table))),  // size checked by the convolution
      convolution_(mesh.n1, mesh.n2, components, *table_, has_symmetric_blocks(*table_, components)),
      padded_index_(mesh.size()) {
  const auto n1 = static_cast<std::size_t>(mesh.n1);
  for (std::size_t k = 0; k < padded_index_.size(); ++k)
    padded_index_[k] = static_cast<std::uint32_t>(
        convolution_.padded_index(static_cast<int>(k % n1), static_cast<int>(k / n1)));
}

InfluenceOperator::InfluenceOperator(const Mesh& mesh, const InfluenceOperator& same_kernels)
    : mesh_(mesh),
      components_(same_kernels.components_),
      table_(same_kernels.table_),
      convolution_(same_kernels.convolution_, detail::FftConvolution::ShareKernels{}),
      padded_index_(same_kernels.padded_index_) {
  require(mesh.n1 == same_kernels.mesh_.n1 && mesh.n2 == same_kernels.mesh_.n2 &&
              mesh.dx1_m == same_kernels.mesh_.dx1_m && mesh.dx2_m == same_kernels.mesh_.dx2_m,
          "influence operator: shared kernels need the same mesh size and element size");
}

void InfluenceOperator::apply_on_grid(std::span<const double> in, std::span<double> out) {
  convolution_.apply(in, out);
}

void InfluenceOperator::add_element_product(std::size_t element, double value, std::span<double> out) const {
  const int n1 = mesh_.n1, n2 = mesh_.n2;
  const int j1 = static_cast<int>(element % static_cast<std::size_t>(n1));
  const int j2 = static_cast<int>(element / static_cast<std::size_t>(n1));
  const std::size_t row_length = static_cast<std::size_t>(2 * n1 - 1);
  for (int i2 = 0; i2 < n2; ++i2) {
    // The kernel's row m2 = i2 − j2, from m1 = −j1 (at i1 = 0) on.
    const double* row = table_->data() + static_cast<std::size_t>(i2 - j2 + n2 - 1) * row_length +
                        static_cast<std::size_t>(n1 - 1 - j1);
    double* u = out.data() + static_cast<std::size_t>(i2) * static_cast<std::size_t>(n1);
    for (int i1 = 0; i1 < n1; ++i1) u[i1] += value * row[i1];
  }
}

void InfluenceOperator::apply(const std::vector<std::size_t>& elements, std::span<const double> x,
                              std::span<double> y) {
  apply(elements, x, y, false);
}

void InfluenceOperator::apply_transpose(const std::vector<std::size_t>& elements, std::span<const double> x,
                                        std::span<double> y) {
  apply(elements, x, y, true);
}

void InfluenceOperator::apply(const std::vector<std::size_t>& elements, std::span<const double> x,
                              std::span<double> y, bool transpose) {
  const std::size_t n = elements.size();
  require(x.size() == n * components_ && y.size() == n * components_, "influence operator: wrong vector size");
  // Scatter straight into the padded transform inputs and gather from the outputs.
  convolution_.clear_inputs();
  for (int c = 0; c < components_; ++c) {
    double* field = convolution_.input(c);
    const double* values = x.data() + static_cast<std::size_t>(c) * n;
    for (std::size_t e = 0; e < n; ++e) field[padded_index_[elements[e]]] = values[e];
  }
  convolution_.convolve(transpose);
  for (int c = 0; c < components_; ++c) {
    const double* field = convolution_.output(c);
    double* values = y.data() + static_cast<std::size_t>(c) * n;
    for (std::size_t e = 0; e < n; ++e) values[e] = field[padded_index_[elements[e]]];
  }
}

Eigen::MatrixXd InfluenceOperator::dense(const std::vector<std::size_t>& elements) const {
  const auto n = static_cast<Eigen::Index>(elements.size());
  Eigen::MatrixXd matrix(components_ * n, components_ * n);
  const auto n1 = static_cast<std::size_t>(mesh_.n1);
  for (int k = 0; k < components_; ++k) {
    for (int l = 0; l < components_; ++l) {
      for (Eigen::Index j = 0; j < n; ++j) {
        const int j1 = static_cast<int>(elements[j] % n1);
        const int j2 = static_cast<int>(elements[j] / n1);
        for (Eigen::Index i = 0; i < n; ++i) {
          const int i1 = static_cast<int>(elements[i] % n1);
          const int i2 = static_cast<int>(elements[i] / n1);
          matrix(k * n + i, l * n + j) = kernel(k, l, i1 - j1, i2 - j2);
        }
      }
    }
  }
  return matrix;
}

InfluenceOperator make_normal_operator(const Mesh& mesh, const Material& material) {
  validate(mesh);
  const ElementTable a = tabulate_element_influence(mesh, material, 0.0, -(mesh.n1 - 1), mesh.n1 - 1);
  return InfluenceOperator(mesh, 1, a.a33);
}

namespace {

InfluenceOperator steady_rolling_operator(const Mesh& mesh, const Material& material, double alpha) {
  // Influence at the collocation points x + alpha dx1/2 for offsets m1 = -(n1-1) .. n1: the
  // upwind difference needs the point one element ahead as well.
  const int lo = -(mesh.n1 - 1), hi = mesh.n1;
  const ElementTable a = tabulate_element_influence(mesh, material, 0.5 * alpha, lo, hi);
  const std::size_t w1 = static_cast<std::size_t>(2 * mesh.n1 - 1);
  const std::size_t w2 = static_cast<std::size_t>(2 * mesh.n2 - 1);
  const std::size_t aw1 = static_cast<std::size_t>(hi - lo + 1);
  std::vector<double> table(4 * w1 * w2);
  const double inv_dx1 = 1.0 / mesh.dx1_m;
  const std::vector<double>* blocks[4] = {&a.a11, &a.a12, &a.a12, &a.a22};
  for (std::size_t b = 0; b < 4; ++b) {
    const std::vector<double>& src = *blocks[b];
    for (std::size_t j2 = 0; j2 < w2; ++j2) {
      const double* row = src.data() + j2 * aw1;
      double* out = table.data() + (b * w2 + j2) * w1;
      for (std::size_t j1 = 0; j1 < w1; ++j1) out[j1] = (row[j1 + 1] - row[j1]) * inv_dx1;
    }
  }
  return InfluenceOperator(mesh, 2, std::move(table));
}

// What the steady-rolling kernels depend on: the mesh's size and element size, the material, alpha.
struct SteadyRollingKey {
  int n1, n2;
  double dx1_m, dx2_m, youngs_modulus_Pa, poisson_ratio, alpha;
  bool operator==(const SteadyRollingKey&) const = default;
};

}  // namespace

InfluenceOperator make_steady_rolling_operator(const Mesh& mesh, const Material& material, double alpha) {
  validate(mesh);
  // The kernels of the last few small meshes are kept per thread and shared (immutable): nH-FastSim
  // builds this operator on its coarse patch (~300 elements) on every call, and tabulating and
  // transforming its kernels was 38 of its ~300 µs (docs/BENCHMARKS.md). In a time step or a sweep
  // at a fixed element size the coarse mesh keeps its size for many calls. Reusing the kernels
  // changes no result. Large meshes (the exact solver's, set up once per solve) are not kept.
  constexpr std::size_t kLargestKeptMesh = 64 * 64;
  constexpr std::size_t kKeptKernels = 8;
  if (mesh.size() > kLargestKeptMesh) return steady_rolling_operator(mesh, material, alpha);
  const SteadyRollingKey key{mesh.n1, mesh.n2, mesh.dx1_m, mesh.dx2_m, material.youngs_modulus_Pa,
                             material.poisson_ratio, alpha};
  thread_local std::vector<std::pair<SteadyRollingKey, std::shared_ptr<const InfluenceOperator>>> recent;
  for (auto it = recent.begin(); it != recent.end(); ++it) {
    if (it->first == key) {
      auto hit = std::move(*it);
      recent.erase(it);
      recent.push_back(std::move(hit));
      return InfluenceOperator(mesh, *recent.back().second);
    }
  }
  auto made = std::make_shared<const InfluenceOperator>(steady_rolling_operator(mesh, material, alpha));
  if (recent.size() == kKeptKernels) recent.erase(recent.begin());
  recent.emplace_back(key, made);
  return InfluenceOperator(mesh, *made);
}

}  // namespace railcontact
