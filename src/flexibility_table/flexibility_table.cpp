// The flexibility table as a value: validation, profile and material checks, interpolation
// (docs/FLEXTABLE.md §2, §4).
#include "railcontact/flexibility_table.hpp"
#include "support/file_fingerprint.hpp"
#include "flexibility_table/table_size.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "railcontact/error.hpp"
#include "railcontact/text_file.hpp"

namespace railcontact {

std::string FileFingerprint::hash_hex() const { return fnv1a64_hex(fnv1a64); }

FileFingerprint file_fingerprint(const std::filesystem::path& path) { return {path.string(), file_fnv1a64(path)}; }

namespace {

constexpr double kMm = 1e-3;

void check_increasing(const std::vector<double>& values, const char* what) {
  for (std::size_t k = 0; k < values.size(); ++k) {
    require(std::isfinite(values[k]), [&] { return fmt::format("flexibility table: the {} must be finite", what); });
    require(k == 0 || values[k] > values[k - 1],
            [&] { return fmt::format("flexibility table: the {} must be strictly increasing", what); });
  }
}

// A solved node's values: finite and physically plausible (a table file may hold anything). The
// message names the node by its index (as in the file, nodes[k]), the key and the allowed range.
void check_node(const FlexibilityTableNode& n, std::size_t index) {
  if (n.status != FlexibilityNodeStatus::solved) return;
  const auto check = [&](const char* key, double value, bool plausible, const char* allowed) {
    require(std::isfinite(value) && plausible, [&] {
      return fmt::format("flexibility table: nodes[{}] (y = {:.4f} mm, Fz = {:g} N): {} = {:g} is not plausible ({})",
                         index, n.y_m / kMm, n.vertical_load_N, key, value, allowed);
    });
  };
  const auto in_open = [](double value, double low, double high) { return value > low && value < high; };
  check("L1_m_per_Pa", n.flexibility.L1, in_open(n.flexibility.L1, 0.0, 1e-6), "0 < L1 < 1e-6 m/Pa");
  check("L2_m_per_Pa", n.flexibility.L2, in_open(n.flexibility.L2, 0.0, 1e-6), "0 < L2 < 1e-6 m/Pa");
  check("L3_m_per_Pa", n.flexibility.L3, in_open(n.flexibility.L3, 0.0, 1e-6), "0 < L3 < 1e-6 m/Pa");
  check("f11_N", n.f11_N, in_open(n.f11_N, 0.0, 1e12), "0 < f11 < 1e12 N");
  check("f22_N", n.f22_N, in_open(n.f22_N, 0.0, 1e12), "0 < f22 < 1e12 N");
  check("f23_Nm", n.f23_Nm, in_open(n.f23_Nm, 0.0, 1e10), "0 < f23 < 1e10 N m");
  require(n.coupling.plausible(), [&] {
    return fmt::format("flexibility table: nodes[{}] (y = {:.4f} mm, Fz = {:g} N): creepage_coupling ({:g}, {:g} m, "
                       "{:g}, {:g} m) is not plausible (ratios within ±1, lengths within ±0.1 m)",
                       index, n.y_m / kMm, n.vertical_load_N, n.coupling.xi_per_eta, n.coupling.xi_per_phi_m,
                       n.coupling.eta_per_xi, n.coupling.eta_per_phi_m);
  });
  check("normal_force_N", n.normal_force_N, n.normal_force_N > 0.0 && n.normal_force_N <= 1e8, "0 < F3 <= 1e8 N");
  check("contact_angle_rad", n.contact_angle_rad, std::abs(n.contact_angle_rad) <= 1.5, "|contact angle| <= 1.5 rad");
  check("spin_per_m", n.spin_per_m, std::abs(n.spin_per_m) <= 100.0, "|spin| <= 100 1/m");
  check("area_m2", n.area_m2, in_open(n.area_m2, 0.0, 0.01), "0 < area < 0.01 m2");
  require(n.elements_in_contact >= 1, [&] {
    return fmt::format("flexibility table: nodes[{}] (y = {:.4f} mm, Fz = {:g} N): elements_in_contact = 0 is not "
                       "plausible (at least 1 for a solved node)",
                       index, n.y_m / kMm, n.vertical_load_N);
  });
}

}  // namespace

void check_table_size(std::size_t y_values, std::size_t loads) {
  const double nodes = static_cast<double>(y_values) * static_cast<double>(loads);
  require(nodes <= kMaximumFlexibilityTableNodes, [&] {
    return fmt::format("flexibility table: {} y values × {} loads = {:g} nodes; at most {:g} nodes are read (a build "
                       "makes at most {} y values, plus the contact-jump brackets, × {} loads)",
                       y_values, loads, nodes, kMaximumFlexibilityTableNodes, kMaximumFlexibilityTableYValues,
                       kMaximumFlexibilityTableLoads);
  });
}

namespace {

// Interpolation weights of one axis: up to two (index, weight) pairs with non-zero weight.
struct AxisWeights {
  std::array<std::size_t, 2> index{};
  std::array<double, 2> weight{};
  int count = 0;
};

AxisWeights one_node(std::size_t k) { return {{k, 0}, {1.0, 0.0}, 1}; }

// Weights of x on the grid (x inside [front, back]); u(x) the interpolation variable (x or log x).
// `nearest` intervals take the nearer node (contact jumps).
template <class Transform>
AxisWeights axis_weights(const std::vector<double>& grid, double x, Transform u, const std::vector<std::uint8_t>* nearest) {
  if (grid.size() == 1) return one_node(0);
  const auto upper = std::upper_bound(grid.begin(), grid.end(), x);
  std::size_t k = static_cast<std::size_t>(std::max<std::ptrdiff_t>(0, upper - grid.begin() - 1));
  k = std::min(k, grid.size() - 2);
  if (x == grid[k]) return one_node(k);
  if (x == grid[k + 1]) return one_node(k + 1);
  const double t = (u(x) - u(grid[k])) / (u(grid[k + 1]) - u(grid[k]));
  if (nearest != nullptr && (*nearest)[k] != 0) return one_node(t < 0.5 ? k : k + 1);
  return {{k, k + 1}, {1.0 - t, t}, 2};
}

}  // namespace

std::string_view flexibility_node_status_name(FlexibilityNodeStatus status) {
  switch (status) {
    case FlexibilityNodeStatus::solved: return "solved";
    case FlexibilityNodeStatus::several_patches: return "several-patches";
    case FlexibilityNodeStatus::failed: return "failed";
  }
  return "?";
}

FlexibilityTable::FlexibilityTable(FlexibilityTableMetadata metadata, std::vector<double> y_m,
                                   std::vector<double> vertical_loads_N, std::vector<FlexibilityTableNode> nodes,
                                   std::vector<ContactJump> contact_jumps)
    : metadata_(std::move(metadata)),
      y_m_(std::move(y_m)),
      loads_N_(std::move(vertical_loads_N)),
      nodes_(std::move(nodes)),
      jumps_(std::move(contact_jumps)) {
  require(!y_m_.empty() && !loads_N_.empty(), "flexibility table: at least one y value and one load are needed");
  check_table_size(y_m_.size(), loads_N_.size());
  check_increasing(y_m_, "y values");
  check_increasing(loads_N_, "vertical loads");
  require(loads_N_.front() > 0.0, "flexibility table: the vertical loads must be positive");
  require(nodes_.size() == y_m_.size() * loads_N_.size(), [&] {
    return fmt::format("flexibility table: {} nodes for {} y values × {} loads", nodes_.size(), y_m_.size(),
                       loads_N_.size());
  });
  validate(metadata_.material);
  for (std::size_t iy = 0; iy < y_m_.size(); ++iy) {
    for (std::size_t il = 0; il < loads_N_.size(); ++il) {
      const FlexibilityTableNode& n = node(iy, il);
      require(n.y_m == y_m_[iy] && n.vertical_load_N == loads_N_[il], [&] {
        return fmt::format("flexibility table: node {} is not on its grid point (y = {:.6g} m, Fz = {:g} N)",
                           iy * loads_N_.size() + il, y_m_[iy], loads_N_[il]);
      });
      check_node(n, iy * loads_N_.size() + il);
    }
  }
  jump_after_.assign(y_m_.size() > 1 ? y_m_.size() - 1 : 0, 0);
  for (const ContactJump& jump : jumps_) {
    require(jump.interval < jump_after_.size() && jump_after_[jump.interval] == 0,
            "flexibility table: a contact jump names a missing or repeated y interval");
    jump_after_[jump.interval] = 1;
  }
  std::sort(jumps_.begin(), jumps_.end(), [](const ContactJump& a, const ContactJump& b) { return a.interval < b.interval; });
}

const FlexibilityTableNode& FlexibilityTable::node(std::size_t iy, std::size_t iload) const {
  if (iy >= y_m_.size() || iload >= loads_N_.size()) throw Error("flexibility table: node index out of range");
  return nodes_[iy * loads_N_.size() + iload];
}

std::string FlexibilityTable::name() const {
  return source_.empty() ? std::string("flexibility table") : "flexibility table " + source_;
}

void FlexibilityTable::check_profiles(const FileFingerprint& wheel, const FileFingerprint& rail) const {
  const FileFingerprint& w = metadata_.wheel_profile;
  const FileFingerprint& r = metadata_.rail_profile;
  if (wheel.fnv1a64 == w.fnv1a64 && rail.fnv1a64 == r.fnv1a64) return;
  throw Error(fmt::format(
      "{} was built for other profiles: wheel {} (fnv1a64 {}), rail {} (fnv1a64 {}); given wheel {} ({}), rail {} ({})",
      name(), w.file, fnv1a64_hex(w.fnv1a64), r.file, fnv1a64_hex(r.fnv1a64), wheel.file, fnv1a64_hex(wheel.fnv1a64),
      rail.file, fnv1a64_hex(rail.fnv1a64)));
}

void FlexibilityTable::check_profiles(const WheelRailPair& pair) const {
  check_profiles(file_fingerprint(pair.wheel().source()), file_fingerprint(pair.rail().source()));
  const TrackWheelsetParameters& a = metadata_.track;
  const TrackWheelsetParameters& b = pair.parameters();
  const bool same = a.track_gauge_m == b.track_gauge_m && a.gauge_measuring_depth_m == b.gauge_measuring_depth_m &&
                    a.flange_back_distance_m == b.flange_back_distance_m && a.flange_back_y_m == b.flange_back_y_m &&
                    a.taping_line_from_flange_back_m == b.taping_line_from_flange_back_m &&
                    a.nominal_rolling_radius_m == b.nominal_rolling_radius_m && a.rail_cant_rad == b.rail_cant_rad;
  require(same, [&] {
    return fmt::format(
        "{} was built for other track and wheelset parameters (gauge {} m, flange back distance {} m, "
        "nominal rolling radius {} m, rail cant {} rad)",
        name(), a.track_gauge_m, a.flange_back_distance_m, a.nominal_rolling_radius_m, a.rail_cant_rad);
  });
}

void FlexibilityTable::check_material(const Material& material, double collocation_offset) const {
  const Material& m = metadata_.material;
  require(material.youngs_modulus_Pa == m.youngs_modulus_Pa && material.poisson_ratio == m.poisson_ratio, [&] {
    return fmt::format("{} was built for another material (E = {:g} Pa, nu = {:g}; given E = {:g} Pa, nu = {:g})",
                       name(), m.youngs_modulus_Pa, m.poisson_ratio, material.youngs_modulus_Pa,
                       material.poisson_ratio);
  });
  require(collocation_offset == metadata_.collocation_offset, [&] {
    return fmt::format("{} was built with the collocation offset alpha = {:g} (given {:g})", name(),
                       metadata_.collocation_offset, collocation_offset);
  });
}

std::string older_nh_fastsim_recipe_note(int nh_fastsim_recipe) {
  // Recipes 3 and 4 have the same flexibilities (4 adds the creepage coupling, stored with them).
  if (nh_fastsim_recipe >= 3) return {};
  return fmt::format(
      "the table was built with an older nH-FastSim recipe ({}; this railcontact: {}): its flexibilities differ from "
      "the ones computed on the fly by up to a few per cent (docs/FLEXTABLE.md \"Tables of older recipes\"); rebuild "
      "it for today's",
      nh_fastsim_recipe == 0 ? std::string("1 or 2, not recorded") : std::to_string(nh_fastsim_recipe),
      kNhFastSimRecipe);
}

void FlexibilityTable::check_recipe(int flexibility_coarsening, double collocation_offset) const {
  require(flexibility_coarsening == metadata_.flexibility_coarsening, [&] {
    const auto described = [](int f) { return f == 0 ? std::string("0 (automatic)") : std::to_string(f); };
    return fmt::format(
        "{} was built with the flexibility coarsening {} and is used with {}: its flexibilities come from another "
        "nH-FastSim recipe (use the table's coarsening, or build a table with this one)",
        name(), described(metadata_.flexibility_coarsening), described(flexibility_coarsening));
  });
  require(collocation_offset == metadata_.collocation_offset, [&] {
    return fmt::format("{} was built with the collocation offset alpha = {:g} (given {:g})", name(),
                       metadata_.collocation_offset, collocation_offset);
  });
}

void FlexibilityTable::check_contact_reference(ContactReference reference) const {
  require(reference == metadata_.contact_reference, [&] {
    return fmt::format("{} was built on the {} contact reference and is used on the {} one (a case's [geometry] "
                       "contact_reference, railcontact patch --reference): use the table's reference, or build a table "
                       "with this one",
                       name(), contact_reference_name(metadata_.contact_reference), contact_reference_name(reference));
  });
}

FlexibilityTableValues FlexibilityTable::lookup(double y_m, double vertical_load_N,
                                                FlexibilityInterpolation interpolation) const {
  return interpolate(y_m, vertical_load_N, 0.0, interpolation);
}

FlexibilityTableValues FlexibilityTable::lookup_for_patch(double y_m, double vertical_load_N, double patch_area_m2,
                                                          FlexibilityInterpolation interpolation) const {
  if (!(std::isfinite(patch_area_m2) && patch_area_m2 > 0.0))
    throw Error(fmt::format("{}: the patch area must be positive (got {} m2)", name(), patch_area_m2));
  return interpolate(y_m, vertical_load_N, patch_area_m2, interpolation);
}

FlexibilityTableValues FlexibilityTable::interpolate(double y_m, double vertical_load_N, double patch_area_m2,
                                                     FlexibilityInterpolation interpolation) const {
  // (No message is formatted on the way: a lookup is part of every simulation step.)
  if (empty()) throw Error("flexibility table: the table is empty");
  if (!(std::isfinite(y_m) && std::isfinite(vertical_load_N) && vertical_load_N > 0.0))
    throw Error(fmt::format("{}: y and Fz must be finite and Fz positive (got y = {} m, Fz = {} N)", name(), y_m,
                            vertical_load_N));
  if (y_m < y_m_.front() || y_m > y_m_.back())
    throw Error(fmt::format("{}: y = {:.4f} mm lies outside its range y = {:.4f} ... {:.4f} mm", name(), y_m / kMm,
                            y_m_.front() / kMm, y_m_.back() / kMm));
  // A single load is held to rounding; several span [first, last].
  const double Fz_min = loads_N_.front(), Fz_max = loads_N_.back();
  const bool single = loads_N_.size() == 1;
  const double slack = single ? 1e-9 * Fz_min : 0.0;
  if (vertical_load_N < Fz_min - slack || vertical_load_N > Fz_max + slack)
    throw Error(single ? fmt::format("{}: Fz = {:g} N lies outside its range: it holds the one vertical load Fz = {:g} N",
                                     name(), vertical_load_N, Fz_min)
                       : fmt::format("{}: Fz = {:g} N lies outside its range Fz = {:g} ... {:g} N", name(),
                                     vertical_load_N, Fz_min, Fz_max));

  const AxisWeights wy = axis_weights(y_m_, y_m, [](double y) { return y; }, &jump_after_);
  const AxisWeights wl = single ? one_node(0)
                                : axis_weights(loads_N_, vertical_load_N, [](double F) { return std::log(F); }, nullptr);
  struct Term {
    const FlexibilityTableNode* node;
    double weight;
  };
  std::array<Term, 4> terms{};
  int count = 0;
  for (int a = 0; a < wy.count; ++a) {
    for (int b = 0; b < wl.count; ++b) {
      const FlexibilityTableNode& n = nodes_[wy.index[a] * loads_N_.size() + wl.index[b]];
      if (n.status != FlexibilityNodeStatus::solved)
        throw Error(fmt::format("{}: no flexibilities at y = {:.4f} mm, Fz = {:g} N: the table has a gap next to the node "
                                "y = {:.4f} mm, Fz = {:g} N ({}{}{})",
                                name(), y_m / kMm, vertical_load_N, n.y_m / kMm, n.vertical_load_N,
                                flexibility_node_status_name(n.status), n.message.empty() ? "" : ": ",
                                printable_excerpt(n.message, 200)));
      terms[count++] = {&n, wy.weight[a] * wl.weight[b]};
    }
  }
  auto sum = [&](auto value) {
    double s = 0.0;
    for (int k = 0; k < count; ++k) s += terms[k].weight * value(*terms[k].node);
    return s;
  };
  auto log_sum = [&](auto value) {
    if (count == 1) return value(*terms[0].node);
    return std::exp(sum([&](const FlexibilityTableNode& n) { return std::log(value(n)); }));
  };

  FlexibilityTableValues v;
  v.y_m = y_m;
  v.vertical_load_N = vertical_load_N;
  v.normal_force_N = log_sum([](const FlexibilityTableNode& n) { return n.normal_force_N; });
  v.contact_angle_rad = sum([](const FlexibilityTableNode& n) { return n.contact_angle_rad; });
  v.spin_per_m = sum([](const FlexibilityTableNode& n) { return n.spin_per_m; });
  v.elements_in_contact = sum([](const FlexibilityTableNode& n) { return static_cast<double>(n.elements_in_contact); });
  const double table_area = log_sum([](const FlexibilityTableNode& n) { return n.area_m2; });
  v.area_m2 = patch_area_m2 > 0.0 ? patch_area_m2 : table_area;
  if (interpolation == FlexibilityInterpolation::plain) {
    v.flexibility.L1 = sum([](const FlexibilityTableNode& n) { return n.flexibility.L1; });
    v.flexibility.L2 = sum([](const FlexibilityTableNode& n) { return n.flexibility.L2; });
    v.flexibility.L3 = sum([](const FlexibilityTableNode& n) { return n.flexibility.L3; });
    v.f11_N = sum([](const FlexibilityTableNode& n) { return n.f11_N; });
    v.f22_N = sum([](const FlexibilityTableNode& n) { return n.f22_N; });
    v.f23_Nm = sum([](const FlexibilityTableNode& n) { return n.f23_Nm; });
    v.coupling.xi_per_eta = sum([](const FlexibilityTableNode& n) { return n.coupling.xi_per_eta; });
    v.coupling.xi_per_phi_m = sum([](const FlexibilityTableNode& n) { return n.coupling.xi_per_phi_m; });
    v.coupling.eta_per_xi = sum([](const FlexibilityTableNode& n) { return n.coupling.eta_per_xi; });
    v.coupling.eta_per_phi_m = sum([](const FlexibilityTableNode& n) { return n.coupling.eta_per_phi_m; });
    return v;
  }
  // Area-scaled: L ∝ √A, f11, f22 ∝ A, f23 ∝ A^1.5 at fixed shape.
  const double root_area = std::sqrt(v.area_m2);
  v.flexibility.L1 = root_area * sum([](const FlexibilityTableNode& n) { return n.flexibility.L1 / std::sqrt(n.area_m2); });
  v.flexibility.L2 = root_area * sum([](const FlexibilityTableNode& n) { return n.flexibility.L2 / std::sqrt(n.area_m2); });
  v.flexibility.L3 = root_area * sum([](const FlexibilityTableNode& n) { return n.flexibility.L3 / std::sqrt(n.area_m2); });
  v.f11_N = v.area_m2 * sum([](const FlexibilityTableNode& n) { return n.f11_N / n.area_m2; });
  v.f22_N = v.area_m2 * sum([](const FlexibilityTableNode& n) { return n.f22_N / n.area_m2; });
  v.f23_Nm = v.area_m2 * root_area * sum([](const FlexibilityTableNode& n) { return n.f23_Nm / (n.area_m2 * std::sqrt(n.area_m2)); });
  // The coupling: its ratios as they are, its lengths (per 1/m of spin) ∝ √A as L.
  v.coupling.xi_per_eta = sum([](const FlexibilityTableNode& n) { return n.coupling.xi_per_eta; });
  v.coupling.eta_per_xi = sum([](const FlexibilityTableNode& n) { return n.coupling.eta_per_xi; });
  v.coupling.xi_per_phi_m = root_area * sum([](const FlexibilityTableNode& n) { return n.coupling.xi_per_phi_m / std::sqrt(n.area_m2); });
  v.coupling.eta_per_phi_m = root_area * sum([](const FlexibilityTableNode& n) { return n.coupling.eta_per_phi_m / std::sqrt(n.area_m2); });
  return v;
}

}  // namespace railcontact
