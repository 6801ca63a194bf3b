// Fuzz target: the wheelset table's evaluation inputs (docs/RELIABILITY.md "Fuzzing"). The tables
// are fixed and real; the input is the state, loads, mu and options of a lookup:
//  - WheelsetTable::evaluate on one of three small tables of fuzz/corpus/wheelset_table/ (two loads;
//    a gap and two yaws; a patch of two lobes), chosen by the first byte;
//  - the C API's rc_wheelset_evaluate_table on a table built at start-up (the default track, 0.5 mm
//    elements, y = -0.5 and 0.5 mm, loads 90 and 110 kN), with fuzzed rc_wheelset_state fields and
//    the options' loads, mu, normal mode, material, element size and slip direction (options that
//    drop the table are set back and the table reloaded).
// Every outcome must be a railcontact::Error (a C status) other than internal, or finite results.
//
// Input: a sequence of values, each one selector byte and its payload: a selector below 40 takes
// the next 8 bytes as a double's bits (NaN, infinities, huge values); otherwise the next 2 bytes
// place a value in a plausible range (a little beyond the table's grid). Missing bytes read as 0.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <unistd.h>

#include "fuzz_target.hpp"
#include "railcontact/railcontact.h"
#include "railcontact/text_file.hpp"
#include "railcontact/wheelset_table.hpp"

namespace {

namespace rc = railcontact;

class Reader {
 public:
  Reader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  std::uint8_t byte() { return pos_ < size_ ? data_[pos_++] : 0; }
  // A value: raw bits, or lo + (hi - lo) × u / 65535.
  double value(double lo, double hi) {
    if (byte() < 40) {
      std::uint64_t bits = 0;
      for (int k = 0; k < 8; ++k) bits = (bits << 8) | byte();
      double x = 0.0;
      std::memcpy(&x, &bits, sizeof x);
      return x;
    }
    const unsigned u = (static_cast<unsigned>(byte()) << 8) | byte();
    return lo + (hi - lo) * static_cast<double>(u) / 65535.0;
  }
  // Zero unless the selector byte is odd (roll, z and the like are mostly zero).
  double mostly_zero(double lo, double hi) { return (byte() & 1) != 0 ? value(lo, hi) : 0.0; }

 private:
  const std::uint8_t* data_;
  std::size_t size_, pos_ = 0;
};

[[noreturn]] void finding(const char* what) {
  std::fprintf(stderr, "railcontact fuzz: %s\n", what);
  std::abort();
}

void require_finite(const rc::Vector3& v, const char* what) {
  for (double x : v)
    if (!std::isfinite(x)) finding(what);
}

void check_finite(const rc::WheelsetResult& r) {
  require_finite(r.force_track_N, "a non-finite wheelset force from the table");
  for (const rc::WheelResult& w : r.wheels) {
    require_finite(w.force_track_N, "a non-finite wheel force from the table");
    if (!std::isfinite(w.vertical_displacement_m)) finding("a non-finite vertical displacement from the table");
    for (const rc::WheelsetPatch& p : w.patches) {
      require_finite(p.region.reference_point_track_m, "a non-finite reference point from the table");
      if (!std::isfinite(p.creepage.xi) || !std::isfinite(p.creepage.eta) || !std::isfinite(p.creepage.phi))
        finding("a non-finite creepage from the table");
      for (const rc::PatchSolverResult& s : p.solvers) {
        if (!std::isfinite(s.forces.F1_N) || !std::isfinite(s.forces.F2_N) || !std::isfinite(s.forces.M3_Nm))
          finding("a non-finite patch force from the table");
        require_finite(s.force_track_N, "a non-finite patch force from the table");
      }
    }
  }
}

const std::vector<rc::WheelsetTable>& tables() {
  static const std::vector<rc::WheelsetTable> loaded = [] {
    std::vector<rc::WheelsetTable> t;
    for (const char* name : {"two_loads.json", "gap_flange_two_yaws.json", "two_lobes.json"})
      t.push_back(rc::load_wheelset_table(std::filesystem::path(RAILCONTACT_FUZZ_CORPUS_DIR) / "wheelset_table" / name));
    return t;
  }();
  return loaded;
}

// The C API's wheelset with its table, built once; `file` keeps the table to reload it.
struct CApiTable {
  rc_wheelset* wheelset = nullptr;
  rc_wheelset_options options{};
  std::string file;
  CApiTable() = default;
  CApiTable(CApiTable&& other) noexcept
      : wheelset(std::exchange(other.wheelset, nullptr)), options(other.options), file(std::move(other.file)) {}
  CApiTable(const CApiTable&) = delete;
  CApiTable& operator=(const CApiTable&) = delete;
  CApiTable& operator=(CApiTable&&) = delete;
  ~CApiTable() {  // at exit: nothing left in the temporary directory
    rc_wheelset_destroy(wheelset);
    if (!file.empty()) std::remove(file.c_str());
  }
};

CApiTable& c_api_table() {
  static CApiTable t = [] {
    CApiTable made;
    if (rc_wheelset_create(&made.wheelset) != RC_OK || rc_wheelset_set_default_track(made.wheelset) != RC_OK)
      finding("the C API wheelset cannot be set up");
    rc_wheelset_options_default(&made.options);
    made.options.element_size_m = 0.5e-3;
    const double y[] = {-0.5e-3, 0.5e-3}, yaw[] = {0.0}, loads[] = {90e3, 110e3};
    made.file = (std::filesystem::temp_directory_path() /
                 ("railcontact_wheelset_table_lookup_fuzz_" + std::to_string(getpid()) + ".json"))
                    .string();
    if (rc_wheelset_set_options(made.wheelset, &made.options) != RC_OK ||
        rc_wheelset_table_build(made.wheelset, y, 2, yaw, 1, loads, 2, nullptr, nullptr) != RC_OK ||
        rc_wheelset_table_save(made.wheelset, made.file.c_str()) != RC_OK)
      finding("the C API wheelset table cannot be built");
    return made;
  }();
  return t;
}

void check_status(rc_status status) {
  if (status == RC_INTERNAL) finding("an internal error from the C API's table");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > 4096) return 0;
  Reader in(data, size);
  // The library: one of the tables, a state around its grid.
  const rc::WheelsetTable& table = tables()[in.byte() % tables().size()];
  const rc::WheelsetTableGrid& grid = table.grid();
  const double y_span = std::max(1e-3, grid.y_m.back() - grid.y_m.front());
  rc::WheelsetState state;
  rc::WheelsetPosition& p = state.position;
  p.lateral_displacement_m = in.value(grid.y_m.front() - 0.1 * y_span, grid.y_m.back() + 0.1 * y_span);
  p.yaw_rad = in.value(-0.012, 0.012);
  p.roll_rad = in.mostly_zero(-0.01, 0.01);
  p.vertical_displacement_m = in.mostly_zero(-0.01, 0.01);
  rc::WheelsetVelocity& v = state.velocity;
  v.forward_speed_m_per_s = in.value(-1.0, 100.0);
  v.lateral_velocity_m_per_s = in.value(-1.0, 1.0);
  v.vertical_velocity_m_per_s = in.mostly_zero(-1.0, 1.0);
  v.roll_rate_rad_per_s = in.mostly_zero(-1.0, 1.0);
  v.yaw_rate_rad_per_s = in.value(-1.0, 1.0);
  v.wheel_angular_velocity_rad_per_s = (in.byte() & 1) != 0 ? in.value(0.0, 300.0) : std::nan("");
  v.extra_longitudinal_creepage = in.value(-0.05, 0.05);
  const double load_lo = grid.wheel_load_N.front() * 0.9, load_hi = grid.wheel_load_N.back() * 1.1;
  const rc::WheelLoads loads{in.value(load_lo, load_hi), in.value(load_lo, load_hi), (in.byte() & 1) != 0};
  const double mu = in.value(-0.1, 1.0);
  rc::fuzz::expect_clean_outcome([&] { check_finite(table.evaluate(state, loads, mu)); });

  // The C API: the state's fields as rc_wheelset_state, the options' loads, mu and settings.
  CApiTable& c = c_api_table();
  rc_wheelset_state s;
  rc_wheelset_state_default(&s);
  s.y_m = in.value(-0.6e-3, 0.6e-3);
  s.z_m = in.mostly_zero(-0.01, 0.01);
  s.roll_rad = in.mostly_zero(-0.01, 0.01);
  s.yaw_rad = in.value(-0.012, 0.012);
  s.forward_speed_m_per_s = in.value(-1.0, 100.0);
  s.lateral_velocity_m_per_s = in.value(-1.0, 1.0);
  s.vertical_velocity_m_per_s = in.mostly_zero(-1.0, 1.0);
  s.roll_rate_rad_per_s = in.mostly_zero(-1.0, 1.0);
  s.yaw_rate_rad_per_s = in.value(-1.0, 1.0);
  s.rotation = static_cast<int>(in.byte() % 3);  // 2: not an rc_wheel_rotation
  s.wheel_angular_velocity_rad_per_s = in.value(0.0, 300.0);
  s.extra_longitudinal_creepage = in.value(-0.05, 0.05);
  rc_wheelset_options o = c.options;
  o.right_load_N = in.value(80e3, 120e3);
  o.left_load_N = in.value(80e3, 120e3);
  o.friction_coefficient = in.value(-0.1, 1.0);
  const std::uint8_t settings = in.byte();
  if ((settings & 1) != 0) o.normal_mode = RC_WHEELSET_BY_POSITION;
  if ((settings & 2) != 0) o.youngs_modulus_Pa = in.value(1e9, 1e12);
  if ((settings & 4) != 0) o.element_size_m = in.value(0.1e-3, 1e-3);
  if ((settings & 8) != 0) o.slip_direction = RC_SLIP_RADIAL;
  if ((settings & 16) != 0) o.balance_roll = 1;
  check_status(rc_wheelset_set_options(c.wheelset, &o));
  rc_wheelset_result r{};
  const rc_status status = rc_wheelset_evaluate_table(c.wheelset, &s, &r);
  check_status(status);
  if (status == RC_OK) {
    for (double x : r.force_track_N)
      if (!std::isfinite(x)) finding("a non-finite force from rc_wheelset_evaluate_table");
    for (const auto& wheel : r.wheel_force_track_N)
      for (double x : wheel)
        if (!std::isfinite(x)) finding("a non-finite wheel force from rc_wheelset_evaluate_table");
  }
  // Back to the table's options; a table the settings dropped is loaded again.
  if (rc_wheelset_set_options(c.wheelset, &c.options) != RC_OK) finding("the C API's options cannot be set back");
  std::size_t ny = 0;
  if (rc_wheelset_table_size(c.wheelset, &ny, nullptr, nullptr) != RC_OK &&
      rc_wheelset_table_load(c.wheelset, c.file.c_str()) != RC_OK)
    finding("the C API's table cannot be loaded again");
  return 0;
}
