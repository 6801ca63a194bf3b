#include "wheel_rail/contact_window.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "elastic/fft_convolution.hpp"
#include "elastic/influence_coefficients.hpp"

namespace railcontact::detail {
namespace {

// [lo, hi] widened by margin, then to a multiple of granule (at most count), within [0, count). A
// long window takes a coarser granule, the largest power of two g with 16 g <= its length (as the
// potential area, WheelsetTrack::potential_contact_area), so that its size repeats from step to step.
void widen(int lo, int hi, int margin, int granule, int count, int& first, int& size) {
  lo = std::max(0, lo - margin);
  hi = std::min(count - 1, hi + margin);
  while (granule * 16 <= hi - lo + 1) granule *= 2;
  size = std::min(count, (hi - lo + 1 + granule - 1) / granule * granule);
  const int extra = size - (hi - lo + 1);
  first = std::clamp(lo - extra / 2, 0, count - size);
}

}  // namespace

std::optional<MeshWindow> pressure_support(const Mesh& mesh, const std::vector<double>& pressure_Pa) {
  int lo1 = mesh.n1, hi1 = -1, lo2 = mesh.n2, hi2 = -1;
  for (int i2 = 0; i2 < mesh.n2; ++i2)
    for (int i1 = 0; i1 < mesh.n1; ++i1)
      if (pressure_Pa[mesh.index(i1, i2)] > 0.0) {
        lo1 = std::min(lo1, i1);
        hi1 = std::max(hi1, i1);
        lo2 = std::min(lo2, i2);
        hi2 = std::max(hi2, i2);
      }
  if (hi1 < 0) return std::nullopt;
  return MeshWindow{lo1, lo2, hi1 - lo1 + 1, hi2 - lo2 + 1};
}

std::optional<MeshWindow> contact_window(const Mesh& mesh, const std::vector<double>& pressure_Pa, int margin,
                                         int granule, double largest_fraction) {
  if (pressure_Pa.size() != mesh.size()) return std::nullopt;
  const std::optional<MeshWindow> support = pressure_support(mesh, pressure_Pa);
  if (!support) return std::nullopt;
  MeshWindow w;
  widen(support->lo1, support->lo1 + support->n1 - 1, margin, granule, mesh.n1, w.lo1, w.n1);
  widen(support->lo2, support->lo2 + support->n2 - 1, margin, granule, mesh.n2, w.lo2, w.n2);
  // The cost that matters is the padded transforms' (fft_convolution.hpp): compare those.
  const auto padded = [](int n1, int n2) {
    return static_cast<double>(fft_friendly_length(2 * n1 - 1)) * fft_friendly_length(2 * n2 - 1);
  };
  if (padded(w.n1, w.n2) > largest_fraction * padded(mesh.n1, mesh.n2)) return std::nullopt;
  return w;
}

Mesh window_mesh(const Mesh& mesh, const MeshWindow& window) {
  Mesh m = mesh;
  m.n1 = window.n1;
  m.n2 = window.n2;
  m.x1_first_m = mesh.x1(window.lo1);
  m.x2_first_m = mesh.x2(window.lo2);
  return m;
}

std::vector<double> cut_window(const Mesh& mesh, const std::vector<double>& field, const MeshWindow& window) {
  std::vector<double> cut(static_cast<std::size_t>(window.n1) * static_cast<std::size_t>(window.n2));
  for (int j2 = 0; j2 < window.n2; ++j2) {
    const auto from = field.begin() + static_cast<std::ptrdiff_t>(mesh.index(window.lo1, window.lo2 + j2));
    std::copy(from, from + window.n1, cut.begin() + static_cast<std::ptrdiff_t>(j2) * window.n1);
  }
  return cut;
}

std::vector<double> paste_window(const Mesh& mesh, const std::vector<double>& window_field, const MeshWindow& window) {
  std::vector<double> field(mesh.size(), 0.0);
  for (int j2 = 0; j2 < window.n2; ++j2) {
    const auto from = window_field.begin() + static_cast<std::ptrdiff_t>(j2) * window.n1;
    std::copy(from, from + window.n1,
              field.begin() + static_cast<std::ptrdiff_t>(mesh.index(window.lo1, window.lo2 + j2)));
  }
  return field;
}

bool contact_on_inner_window_edge(const Mesh& mesh, const MeshWindow& window,
                                  const std::vector<double>& window_pressure_Pa) {
  const bool low1 = window.lo1 > 0, high1 = window.lo1 + window.n1 < mesh.n1;
  const bool low2 = window.lo2 > 0, high2 = window.lo2 + window.n2 < mesh.n2;
  const auto loaded = [&](int j1, int j2) {
    return window_pressure_Pa[static_cast<std::size_t>(j2) * window.n1 + static_cast<std::size_t>(j1)] > 0.0;
  };
  for (int j1 = 0; j1 < window.n1; ++j1)
    if ((low2 && loaded(j1, 0)) || (high2 && loaded(j1, window.n2 - 1))) return true;
  for (int j2 = 0; j2 < window.n2; ++j2)
    if ((low1 && loaded(0, j2)) || (high1 && loaded(window.n1 - 1, j2))) return true;
  return false;
}

NormalInfluenceBound::NormalInfluenceBound(double dx1_m, double dx2_m, const Material& material)
    : dx1_m_(dx1_m), dx2_m_(dx2_m), material_(material), exact_(static_cast<std::size_t>(kExact) * kExact) {
  for (int d2 = 0; d2 < kExact; ++d2)
    for (int d1 = 0; d1 < kExact; ++d1)
      exact_[static_cast<std::size_t>(d2) * kExact + d1] =
          normal_influence(d1 * dx1_m, d2 * dx2_m, ElementSize{dx1_m, dx2_m}, material);
}

double NormalInfluenceBound::at(int d1, int d2) const {
  if (d1 < kExact && d2 < kExact) return exact_[static_cast<std::size_t>(d2) * kExact + d1];
  const double r = std::hypot(d1 * dx1_m_, d2 * dx2_m_) - 0.5 * std::hypot(dx1_m_, dx2_m_);
  return (1.0 - material_.poisson_ratio) / (M_PI * material_.shear_modulus_Pa()) * dx1_m_ * dx2_m_ / r;
}

bool window_solution_holds_outside(const Mesh& mesh, const std::vector<double>& h_m, const MeshWindow& window,
                                   const std::vector<double>& pressure_Pa, const WholeAreaCheck& check,
                                   const NormalInfluenceBound& influence) {
  const Mesh& c = check.mesh;
  if (c.dx1_m != mesh.dx1_m || c.dx2_m != mesh.dx2_m) return false;
  // Element (i1, i2) of this mesh is element (i1 + shift1, i2 + shift2) of the check's; the
  // columns [on1_lo, on1_hi) and rows [on2_lo, on2_hi) of this mesh lie on the check's. Loops run
  // row by row (the rows are contiguous).
  const int shift1 = static_cast<int>(std::lround((mesh.x1_first_m - c.x1_first_m) / mesh.dx1_m));
  const int shift2 = static_cast<int>(std::lround((mesh.x2_first_m - c.x2_first_m) / mesh.dx2_m));
  const int on1_lo = std::clamp(-shift1, 0, mesh.n1), on1_hi = std::clamp(c.n1 - shift1, on1_lo, mesh.n1);
  const int on2_lo = std::clamp(-shift2, 0, mesh.n2), on2_hi = std::clamp(c.n2 - shift2, on2_lo, mesh.n2);
  const auto n1 = static_cast<std::size_t>(mesh.n1);
  const auto on_check_row = [&](int i2) { return on1_lo < on1_hi && i2 >= on2_lo && i2 < on2_hi; };
  const auto check_row = [&](int i2) {  // the check's values of row i2 from column on1_lo on
    return static_cast<std::size_t>(i2 + shift2) * static_cast<std::size_t>(c.n1) +
           static_cast<std::size_t>(on1_lo + shift1);
  };
  // The checked pressure must lie on this mesh (its product is then this mesh's product of it):
  // its support, a box, within the columns and rows of this mesh that lie on the check's.
  const std::optional<MeshWindow> support = check.support ? *check.support : pressure_support(c, check.pressure_Pa);
  if (support && (support->lo1 - shift1 < on1_lo || support->lo1 + support->n1 - shift1 > on1_hi ||
                  support->lo2 - shift2 < on2_lo || support->lo2 + support->n2 - shift2 > on2_hi))
    return false;
  // ||p − p_c||_1 and the bounding box of the elements where they differ, over the window (p is zero
  // outside it) and the check's support moved onto this mesh (p_c is zero outside it).
  int box_lo1 = window.lo1, box_hi1 = window.lo1 + window.n1, box_lo2 = window.lo2, box_hi2 = window.lo2 + window.n2;
  if (support) {
    box_lo1 = std::min(box_lo1, support->lo1 - shift1);
    box_hi1 = std::max(box_hi1, support->lo1 + support->n1 - shift1);
    box_lo2 = std::min(box_lo2, support->lo2 - shift2);
    box_hi2 = std::max(box_hi2, support->lo2 + support->n2 - shift2);
  }
  double pressure_change_Pa = 0.0;  // the sum of the elements' |Δp|
  int lo1 = mesh.n1, hi1 = -1, lo2 = mesh.n2, hi2 = -1;
  for (int i2 = box_lo2; i2 < box_hi2; ++i2) {
    const double* p = pressure_Pa.data() + static_cast<std::size_t>(i2) * n1;
    const bool row_on = on_check_row(i2);
    const double* checked = row_on ? check.pressure_Pa.data() + check_row(i2) : nullptr;  // from column on1_lo
    for (int i1 = box_lo1; i1 < box_hi1; ++i1) {
      const double before = row_on && i1 >= on1_lo && i1 < on1_hi ? checked[i1 - on1_lo] : 0.0;
      const double difference = std::abs(p[i1] - before);
      if (difference == 0.0) continue;
      pressure_change_Pa += difference;
      lo1 = std::min(lo1, i1);
      hi1 = std::max(hi1, i1);
      lo2 = std::min(lo2, i2);
      hi2 = std::max(hi2, i2);
    }
  }
  // Every element outside the window: a row's columns before and after the window where the row
  // crosses it, the whole row elsewhere.
  for (int i2 = 0; i2 < mesh.n2; ++i2) {
    const bool row_inside = i2 >= window.lo2 && i2 < window.lo2 + window.n2;
    const bool row_on = on_check_row(i2);
    const double* h = h_m.data() + static_cast<std::size_t>(i2) * n1;
    const double* u = row_on ? check.displacement_m.data() + check_row(i2) : nullptr;  // from column on1_lo
    const auto holds = [&](int from1, int to1) {
      for (int i1 = from1; i1 < to1; ++i1) {
        if (h[i1] >= 0.0) continue;  // A p >= 0
        if (!row_on || i1 < on1_lo || i1 >= on1_hi) return false;
        double lower = u[i1 - on1_lo];
        if (pressure_change_Pa > 0.0) {
          const int d1 = std::max({0, lo1 - i1, i1 - hi1}), d2 = std::max({0, lo2 - i2, i2 - hi2});
          lower -= influence.at(d1, d2) * pressure_change_Pa;
        }
        if (h[i1] + lower < 0.0) return false;
      }
      return true;
    };
    const bool row_holds = row_inside ? holds(0, window.lo1) && holds(window.lo1 + window.n1, mesh.n1) : holds(0, mesh.n1);
    if (!row_holds) return false;
  }
  return true;
}

}  // namespace railcontact::detail
