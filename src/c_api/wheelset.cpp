// The C API's wheelset (include/railcontact/railcontact.h, docs/C_API.md "Wheelset"): rc_wheelset
// over railcontact::Wheelset (docs/WHEELSET.md). Every field of the C structs is checked (finite,
// enumerations known) before the library's own checks; the batch runs one Wheelset per thread,
// each state from a cold start, so that its numbers do not depend on the threads.
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <thread>
#include <vector>

#include "c_api/c_api_internal.hpp"
#include "railcontact/geometry.hpp"
#include "railcontact/wheel_rail.hpp"

using railcontact::Error;
using railcontact::ErrorKind;
using railcontact::require;
using railcontact::c_api::guarded;
using railcontact::c_api::LastError;
using railcontact::c_api::StatusError;

namespace {

namespace rc = railcontact;

void require_pointer(const void* pointer, const char* what) {
  if (pointer == nullptr) throw Error(fmt::format("{} is null", what));
}

void require_finite(double value, const char* structure, const char* field, const char* unit) {
  require(std::isfinite(value), [&] { return fmt::format("{}.{} = {}{} is not finite", structure, field, value, unit); });
}

void require_flag(int value, const char* field) {
  require(value == 0 || value == 1,
          [&] { return fmt::format("rc_wheelset_options.{} = {} must be 0 or 1", field, value); });
}

rc::TangentialSolver solver_of(int method, const char* field = "solvers") {
  return rc::c_api::method_of(method, fmt::format("rc_wheelset_options.{}", field));
}
rc::WheelsetOptions options_of(const rc_wheelset_options& o) {
  const char* s = "rc_wheelset_options";
  require_finite(o.youngs_modulus_Pa, s, "youngs_modulus_Pa", " Pa");
  require_finite(o.poisson_ratio, s, "poisson_ratio", "");
  require_finite(o.friction_coefficient, s, "friction_coefficient", "");
  require_finite(o.element_size_m, s, "element_size_m", " m");
  require_finite(o.right_load_N, s, "right_load_N", " N");
  require_finite(o.left_load_N, s, "left_load_N", " N");
  require(o.normal_mode == RC_WHEELSET_BY_LOAD || o.normal_mode == RC_WHEELSET_BY_POSITION, [&] {
    return fmt::format("rc_wheelset_options.normal_mode = {} is not an rc_wheelset_normal (0 by load, 1 by position)",
                       o.normal_mode);
  });
  require_flag(o.balance_roll, "balance_roll");
  require_flag(o.tangential_in_balance, "tangential_in_balance");
  require_flag(o.allow_wheel_lift, "allow_wheel_lift");
  require_flag(o.warm_start, "warm_start");
  require(o.solver_count >= 1 && o.solver_count <= 4, [&] {
    return fmt::format("rc_wheelset_options.solver_count = {} must lie in [1, 4]", o.solver_count);
  });
  rc::WheelsetOptions options;
  options.nh_fastsim.bound.slip_direction = rc::c_api::slip_direction_of(o.slip_direction, s);
  options.material = rc::Material{o.youngs_modulus_Pa, o.poisson_ratio};
  options.friction_coefficient = o.friction_coefficient;
  options.element_size_m = o.element_size_m;
  options.solvers.clear();
  for (int k = 0; k < o.solver_count; ++k) {
    const rc::TangentialSolver solver = solver_of(o.solvers[k]);
    require(std::find(options.solvers.begin(), options.solvers.end(), solver) == options.solvers.end(), [&] {
      return fmt::format("rc_wheelset_options.solvers: {} is given twice", rc::solver_name(solver));
    });
    options.solvers.push_back(solver);
  }
  if (o.balance_solver != -1) {
    const rc::TangentialSolver balance = solver_of(o.balance_solver, "balance_solver");
    require(std::find(options.solvers.begin(), options.solvers.end(), balance) != options.solvers.end(), [&] {
      return fmt::format("rc_wheelset_options.balance_solver = {} ({}) is not one of solvers; -1 for the first of them",
                         o.balance_solver, rc::solver_name(balance));
    });
    options.balance_solver = balance;
  }
  require(o.reference_weighting == RC_WEIGHTING_SQUARED_GAP || o.reference_weighting == RC_WEIGHTING_DEPTH, [&] {
    return fmt::format("rc_wheelset_options.reference_weighting = {} is not an rc_reference_weighting (0 squared gap, "
                       "1 depth)",
                       o.reference_weighting);
  });
  options.search.weighting = o.reference_weighting == RC_WEIGHTING_DEPTH ? rc::ReferenceWeighting::depth
                                                                          : rc::ReferenceWeighting::squared_gap;
  require(o.contact_surface == RC_SURFACE_PLANAR || o.contact_surface == RC_SURFACE_CONFORMAL ||
              o.contact_surface == RC_SURFACE_AUTO,
          [&] {
            return fmt::format("rc_wheelset_options.contact_surface = {} is not an rc_contact_surface (0 planar, "
                               "1 conformal, 2 auto)",
                               o.contact_surface);
          });
  options.contact_surface = o.contact_surface == RC_SURFACE_CONFORMAL ? rc::ContactSurface::conformal
                            : o.contact_surface == RC_SURFACE_AUTO    ? rc::ContactSurface::automatic
                                                                      : rc::ContactSurface::planar;
  if (o.normal_mode == RC_WHEELSET_BY_LOAD)
    options.loads = rc::WheelLoads{o.right_load_N, o.left_load_N, o.balance_roll != 0};
  else
    options.loads.reset();
  options.tangential_forces_in_vertical_balance = o.tangential_in_balance != 0;
  options.allow_wheel_lift = o.allow_wheel_lift != 0;
  rc::validate(options);
  return options;
}

rc::WheelsetState state_of(const rc_wheelset_state& c) {
  const char* s = "rc_wheelset_state";
  require_finite(c.y_m, s, "y_m", " m");
  require_finite(c.z_m, s, "z_m", " m");
  require_finite(c.roll_rad, s, "roll_rad", " rad");
  require_finite(c.yaw_rad, s, "yaw_rad", " rad");
  require_finite(c.forward_speed_m_per_s, s, "forward_speed_m_per_s", " m/s");
  require_finite(c.lateral_velocity_m_per_s, s, "lateral_velocity_m_per_s", " m/s");
  require_finite(c.vertical_velocity_m_per_s, s, "vertical_velocity_m_per_s", " m/s");
  require_finite(c.roll_rate_rad_per_s, s, "roll_rate_rad_per_s", " rad/s");
  require_finite(c.yaw_rate_rad_per_s, s, "yaw_rate_rad_per_s", " rad/s");
  require_finite(c.wheel_angular_velocity_rad_per_s, s, "wheel_angular_velocity_rad_per_s", " rad/s");
  require_finite(c.extra_longitudinal_creepage, s, "extra_longitudinal_creepage", "");
  require(c.rotation == RC_ROTATION_ROLLING || c.rotation == RC_ROTATION_GIVEN || c.rotation == RC_ROTATION_FREE, [&] {
    return fmt::format("rc_wheelset_state.rotation = {} is not an rc_wheel_rotation (0 rolling, 1 given, 2 free)",
                       c.rotation);
  });
  rc::WheelsetState state;
  state.position.lateral_displacement_m = c.y_m;
  state.position.vertical_displacement_m = c.z_m;
  state.position.roll_rad = c.roll_rad;
  state.position.yaw_rad = c.yaw_rad;
  rc::WheelsetVelocity& v = state.velocity;
  v.forward_speed_m_per_s = c.forward_speed_m_per_s;
  v.lateral_velocity_m_per_s = c.lateral_velocity_m_per_s;
  v.vertical_velocity_m_per_s = c.vertical_velocity_m_per_s;
  v.roll_rate_rad_per_s = c.roll_rate_rad_per_s;
  v.yaw_rate_rad_per_s = c.yaw_rate_rad_per_s;
  v.extra_longitudinal_creepage = c.extra_longitudinal_creepage;
  if (c.rotation == RC_ROTATION_GIVEN) {
    v.wheel_angular_velocity_rad_per_s = c.wheel_angular_velocity_rad_per_s;
    v.extra_longitudinal_creepage = 0.0;
  }  // else NaN: pure rolling with the extra creepage (WheelsetVelocity)
  if (c.rotation == RC_ROTATION_FREE) {
    v.free_rolling = true;
    v.extra_longitudinal_creepage = 0.0;
  }
  static const rc::WheelsetVelocityNames names{
      "rc_wheelset_state.forward_speed_m_per_s", "rc_wheelset_state.lateral_velocity_m_per_s",
      "rc_wheelset_state.vertical_velocity_m_per_s", "rc_wheelset_state.roll_rate_rad_per_s",
      "rc_wheelset_state.yaw_rate_rad_per_s", "rc_wheelset_state.wheel_angular_velocity_rad_per_s",
      "rc_wheelset_state.extra_longitudinal_creepage"};
  rc::validate(state.velocity, names);
  return state;
}

int datum_of(rc::NominalRadiusDatum datum) {
  return datum == rc::NominalRadiusDatum::taping_line ? RC_RADIUS_AT_TAPING_LINE : RC_RADIUS_AT_PROFILE_ORIGIN;
}

rc::TrackWheelsetParameters track_of(const rc_track_parameters* t) {
  rc::TrackWheelsetParameters p;
  if (t == nullptr) return p;
  const char* s = "rc_track_parameters";
  require_finite(t->track_gauge_m, s, "track_gauge_m", " m");
  require_finite(t->gauge_measuring_depth_m, s, "gauge_measuring_depth_m", " m");
  require_finite(t->flange_back_distance_m, s, "flange_back_distance_m", " m");
  require_finite(t->flange_back_y_m, s, "flange_back_y_m", " m");
  require_finite(t->taping_line_from_flange_back_m, s, "taping_line_from_flange_back_m", " m");
  require_finite(t->nominal_rolling_radius_m, s, "nominal_rolling_radius_m", " m");
  require_finite(t->rail_cant_rad, s, "rail_cant_rad", " rad");
  p.track_gauge_m = t->track_gauge_m;
  p.gauge_measuring_depth_m = t->gauge_measuring_depth_m;
  p.flange_back_distance_m = t->flange_back_distance_m;
  p.flange_back_y_m = t->flange_back_y_m;
  p.taping_line_from_flange_back_m = t->taping_line_from_flange_back_m;
  p.nominal_rolling_radius_m = t->nominal_rolling_radius_m;
  p.rail_cant_rad = t->rail_cant_rad;
  require(t->nominal_radius_at == RC_RADIUS_AT_PROFILE_ORIGIN || t->nominal_radius_at == RC_RADIUS_AT_TAPING_LINE, [&] {
    return fmt::format("rc_track_parameters.nominal_radius_at = {} is not an rc_nominal_radius_datum (0 profile "
                       "origin, 1 taping line)",
                       t->nominal_radius_at);
  });
  p.nominal_radius_at = t->nominal_radius_at == RC_RADIUS_AT_TAPING_LINE ? rc::NominalRadiusDatum::taping_line
                                                                         : rc::NominalRadiusDatum::profile_origin;
  rc::validate(p, "rc_track_parameters.");
  return p;
}

void copy3(const rc::Vector3& v, double out[3]) {
  out[0] = v[0];
  out[1] = v[1];
  out[2] = v[2];
}

rc_wheelset_patch patch_of(const rc::WheelsetPatch& p) {
  rc_wheelset_patch c{};
  copy3(p.region.reference_point_track_m, c.reference_point_track_m);
  copy3(p.region.x2_axis, c.x2_axis);
  copy3(p.region.x3_axis, c.x3_axis);
  c.contact_angle_rad = p.region.contact_angle_rad;
  c.rolling_radius_m = p.rolling_radius_m;
  c.max_interpenetration_m = p.region.max_interpenetration_m;
  c.creepage = rc_creepage{p.creepage.xi, p.creepage.eta, p.creepage.phi};
  c.normal_force_N = p.normal_force_N;
  c.area_m2 = p.area_m2;
  c.max_pressure_Pa = p.max_pressure_Pa;
  c.pressure_centre_x1_m = p.pressure_centre_x1_m;
  c.pressure_centre_x2_m = p.pressure_centre_x2_m;
  const std::size_t n = std::min<std::size_t>(p.solvers.size(), 4);
  for (std::size_t k = 0; k < n; ++k) {
    const rc::PatchSolverResult& s = p.solvers[k];
    c.forces[k] = rc_forces{s.forces.F1_N, s.forces.F2_N, s.forces.M3_Nm, s.adhesion_fraction};
    copy3(s.force_track_N, c.force_track_N[k]);
  }
  copy3(p.pressure_force_track_N, c.pressure_force_track_N);
  c.contact_angle_spread_rad = p.region.contact_angle_spread_rad;
  c.conformal_weight = p.conformal_weight;
  c.side = p.side == rc::WheelSide::right ? RC_WHEEL_RIGHT : RC_WHEEL_LEFT;
  c.elements_in_contact = static_cast<int>(p.elements_in_contact);
  c.normal_iterations = p.normal_iterations;
  c.solver_count = static_cast<int>(n);
  return c;
}

rc_wheelset_result result_of(const rc::WheelsetResult& r) {
  rc_wheelset_result c{};
  copy3(r.force_track_N, c.force_track_N);
  for (std::size_t k = 0; k < 2; ++k) {
    const rc::WheelResult& w = r.wheels[k];
    copy3(w.force_track_N, c.wheel_force_track_N[k]);
    c.wheel_vertical_displacement_m[k] = w.vertical_displacement_m;
    c.patch_count[k] = static_cast<int>(w.patches.size());
    c.load_iterations[k] = w.load_iterations;
  }
  c.vertical_displacement_m = r.state.position.vertical_displacement_m;
  c.roll_rad = r.state.position.roll_rad;
  return c;
}

std::size_t side_index(int side) {
  require(side == RC_WHEEL_RIGHT || side == RC_WHEEL_LEFT,
          [&] { return fmt::format("side = {} is not an rc_wheel_side (0 right, 1 left)", side); });
  return static_cast<std::size_t>(side);
}

rc::Wheelset& require_wheelset(rc_wheelset* w) {
  if (!w->wheelset)
    throw Error("the wheelset has no track (rc_wheelset_set_default_track, rc_wheelset_set_track or "
                "rc_wheelset_set_track_profiles first)");
  return *w->wheelset;
}

const rc::WheelsetResult& require_result(const rc_wheelset* w) {
  if (!w->last) throw Error("no state has been evaluated on this wheelset yet (rc_wheelset_evaluate first)");
  return *w->last;
}

rc::Profile profile(const char* path, const char* what, rc::ProfileKind role) {
  require_pointer(path, what);
  return rc::read_profile(path, rc::ProfileReadOptions{.role = role});
}

// The fields of rc_wheelset_options behind a table's setting (docs/C_API.md "The wheelset table").
const char* options_field(rc::WheelsetTableSetting setting) {
  switch (setting) {
    case rc::WheelsetTableSetting::material: return "youngs_modulus_Pa, poisson_ratio";
    case rc::WheelsetTableSetting::element_size: return "element_size_m";
    case rc::WheelsetTableSetting::slip_direction: return "slip_direction";
    case rc::WheelsetTableSetting::contact_definition: return "reference_weighting";
    case rc::WheelsetTableSetting::contact_surface: return "contact_surface";
    default: return "not an option: rebuild the table";
  }
}

// Empty when `table` was built for this track and these options; else what differs, e.g.
// "element-size 0.2 mm (rc_wheelset_options.element_size_m) differs from the table's 0.5 mm".
std::string table_misfit(const rc::WheelsetTable& table, const rc::Wheelset& wheelset) {
  try {
    table.check_track(wheelset.track());
  } catch (const Error& e) {
    return e.what();
  }
  std::string misfit;
  for (const rc::WheelsetTableMismatch& m : table.mismatches(wheelset.options()))
    misfit += fmt::format("{}{} {} (rc_wheelset_options: {}) differs from the table's {}", misfit.empty() ? "" : "; ",
                          rc::wheelset_table_setting_name(m.setting), m.requested, options_field(m.setting), m.table);
  return misfit;
}

// After a call that changed the track or the options: the table stays only while it was built for
// them; otherwise it is dropped, and rc_wheelset_evaluate_table names the call and what differs.
void recheck_table(rc_wheelset* w, const char* call) {
  if (!w->table) return;
  const std::string misfit = w->wheelset ? table_misfit(*w->table, *w->wheelset) : std::string("no track");
  if (misfit.empty()) return;
  w->table.reset();
  w->table_dropped = fmt::format("{} dropped it: {}", call, misfit);
}

void set_track(rc_wheelset* w, rc::WheelsetTrack track, const char* call) {
  w->last.reset();
  w->wheelset.reset();
  w->wheelset.emplace(std::move(track), options_of(w->options));
  recheck_table(w, call);
}

// Batch: a contiguous range of states on one worker.
struct BatchJob {
  const rc::Wheelset* prototype = nullptr;
  const rc_wheelset_state* states = nullptr;
  rc_wheelset_result* results = nullptr;
  std::size_t patches_per_wheel = 0;
  rc_wheelset_patch* patches = nullptr;
  std::vector<rc_status>* statuses = nullptr;
  std::vector<std::string>* messages = nullptr;
};

void run_batch_range(const BatchJob& job, std::size_t begin, std::size_t end) noexcept {
  LastError error;
  std::optional<rc::Wheelset> worker;
  const rc_status made = guarded(&error, [&] { worker.emplace(*job.prototype); });
  for (std::size_t k = begin; k < end; ++k) {
    rc_status status = made;
    if (status == RC_OK) {
      status = guarded(&error, [&] {
        const rc::WheelsetState state = state_of(job.states[k]);
        if (k != begin) *worker = *job.prototype;  // a cold start for every state (a copy starts cold)
        const rc::WheelsetResult r = worker->evaluate(state);
        job.results[k] = result_of(r);
        std::size_t too_many = 0;
        for (std::size_t w = 0; w < 2; ++w) {
          const std::vector<rc::WheelsetPatch>& ps = r.wheels[w].patches;
          if (ps.size() > job.patches_per_wheel) too_many = std::max(too_many, ps.size());
          if (job.patches == nullptr) continue;
          rc_wheelset_patch* out = job.patches + (2 * k + w) * job.patches_per_wheel;
          for (std::size_t j = 0; j < std::min(ps.size(), job.patches_per_wheel); ++j) out[j] = patch_of(ps[j]);
        }
        if (too_many > 0 && job.patches != nullptr)
          throw StatusError{RC_BUFFER_TOO_SMALL,
                            fmt::format("rc_wheelset_batch_evaluate: a wheel has {} patches; patches_per_wheel = {}",
                                        too_many, job.patches_per_wheel)};
      });
    }
    (*job.statuses)[k] = status;
    if (status != RC_OK) {
      try {
        (*job.messages)[k] = error.message();
      } catch (...) {
      }
    }
  }
}

std::vector<double> finite_grid(const double* values, std::size_t count, const char* what) {
  require(count >= 1 && count <= 20000, [&] { return fmt::format("{}: {} values; 1 to 20000 are allowed", what, count); });
  require_pointer(values, what);
  std::vector<double> v(values, values + count);
  for (std::size_t k = 0; k < v.size(); ++k)
    require(std::isfinite(v[k]), [&] { return fmt::format("{}[{}] = {} is not finite", what, k, v[k]); });
  return v;
}

struct TableBuildCancelled {};

const rc::WheelsetTable& require_table(const rc_wheelset* w) {
  if (!w->table) {
    if (!w->table_dropped.empty())
      throw Error(fmt::format("the wheelset has no table: {} (rc_wheelset_table_build or rc_wheelset_table_load for "
                              "the wheelset as it is)",
                              w->table_dropped));
    throw Error("the wheelset has no table (rc_wheelset_table_build or rc_wheelset_table_load first)");
  }
  return *w->table;
}

}  // namespace

rc_wheelset::rc_wheelset() { rc_wheelset_options_default(&options); }

extern "C" {

rc_status rc_track_parameters_default(rc_track_parameters* t) {
  if (t == nullptr) return RC_INVALID_INPUT;
  const rc::TrackWheelsetParameters p;
  t->track_gauge_m = p.track_gauge_m;
  t->gauge_measuring_depth_m = p.gauge_measuring_depth_m;
  t->flange_back_distance_m = p.flange_back_distance_m;
  t->flange_back_y_m = p.flange_back_y_m;
  t->taping_line_from_flange_back_m = p.taping_line_from_flange_back_m;
  t->nominal_rolling_radius_m = p.nominal_rolling_radius_m;
  t->nominal_radius_at = datum_of(p.nominal_radius_at);
  t->rail_cant_rad = p.rail_cant_rad;
  return RC_OK;
}

rc_status rc_wheelset_options_default(rc_wheelset_options* o) {
  if (o == nullptr) return RC_INVALID_INPUT;
  const rc::WheelsetOptions d;
  *o = rc_wheelset_options{};
  o->youngs_modulus_Pa = d.material.youngs_modulus_Pa;
  o->poisson_ratio = d.material.poisson_ratio;
  o->friction_coefficient = d.friction_coefficient;
  o->element_size_m = d.element_size_m;
  o->right_load_N = d.loads ? d.loads->right_N : 98100.0;
  o->left_load_N = d.loads ? d.loads->left_N : 98100.0;
  o->normal_mode = d.loads ? RC_WHEELSET_BY_LOAD : RC_WHEELSET_BY_POSITION;
  o->balance_roll = d.loads && d.loads->balance_roll ? 1 : 0;
  o->tangential_in_balance = d.tangential_forces_in_vertical_balance ? 1 : 0;
  o->allow_wheel_lift = d.allow_wheel_lift ? 1 : 0;
  o->warm_start = 1;
  switch (d.nh_fastsim.bound.slip_direction) {
    case rc::SlipDirection::radial: o->slip_direction = RC_SLIP_RADIAL; break;
    case rc::SlipDirection::flexibility_weighted: o->slip_direction = RC_SLIP_FLEXIBILITY_WEIGHTED; break;
    case rc::SlipDirection::rigid_slip: o->slip_direction = RC_SLIP_RIGID; break;
    case rc::SlipDirection::elastic_slip: o->slip_direction = RC_SLIP_ELASTIC; break;
  }
  o->solver_count = 1;
  o->solvers[0] = RC_METHOD_NH_FASTSIM;
  o->balance_solver = -1;
  o->reference_weighting =
      d.search.weighting == rc::ReferenceWeighting::depth ? RC_WEIGHTING_DEPTH : RC_WEIGHTING_SQUARED_GAP;
  o->contact_surface = RC_SURFACE_PLANAR;
  return RC_OK;
}

rc_status rc_wheelset_state_default(rc_wheelset_state* s) {
  if (s == nullptr) return RC_INVALID_INPUT;
  *s = rc_wheelset_state{};
  s->forward_speed_m_per_s = rc::WheelsetVelocity{}.forward_speed_m_per_s;
  s->rotation = RC_ROTATION_ROLLING;
  return RC_OK;
}

rc_status rc_wheelset_create(rc_wheelset** wheelset) { return railcontact::c_api::create_handle(wheelset); }

rc_status rc_wheelset_destroy(rc_wheelset* wheelset) {
  delete wheelset;
  return RC_OK;
}

rc_status rc_wheelset_last_error(const rc_wheelset* wheelset, char* buffer, size_t size, size_t* length) {
  return railcontact::c_api::last_error(wheelset, buffer, size, length);
}

rc_status rc_wheelset_set_default_track(rc_wheelset* w) {
  if (w == nullptr) return RC_INVALID_INPUT;
  return guarded(&w->error, [&] { set_track(w, rc::default_wheelset_track(), "rc_wheelset_set_default_track"); });
}

rc_status rc_wheelset_set_track(rc_wheelset* w, const char* wheel_profile_path, const char* rail_profile_path,
                                const rc_track_parameters* track) {
  if (w == nullptr) return RC_INVALID_INPUT;
  return guarded(&w->error, [&] {
    const rc::TrackWheelsetParameters parameters = track_of(track);
    const rc::Profile wheel = profile(wheel_profile_path, "rc_wheelset_set_track: wheel_profile_path", rc::ProfileKind::wheel);
    const rc::Profile rail = profile(rail_profile_path, "rc_wheelset_set_track: rail_profile_path", rc::ProfileKind::rail);
    set_track(w, rc::WheelsetTrack(wheel, rail, parameters), "rc_wheelset_set_track");
  });
}

rc_status rc_wheelset_set_track_profiles(rc_wheelset* w, const char* right_wheel_path, const char* left_wheel_path,
                                         const char* right_rail_path, const char* left_rail_path,
                                         const rc_track_parameters* track) {
  if (w == nullptr) return RC_INVALID_INPUT;
  return guarded(&w->error, [&] {
    const rc::TrackWheelsetParameters parameters = track_of(track);
    rc::WheelsetProfiles profiles;
    profiles.right_wheel = profile(right_wheel_path, "rc_wheelset_set_track_profiles: right_wheel_path", rc::ProfileKind::wheel);
    profiles.left_wheel = profile(left_wheel_path, "rc_wheelset_set_track_profiles: left_wheel_path", rc::ProfileKind::wheel);
    profiles.right_rail = profile(right_rail_path, "rc_wheelset_set_track_profiles: right_rail_path", rc::ProfileKind::rail);
    profiles.left_rail = profile(left_rail_path, "rc_wheelset_set_track_profiles: left_rail_path", rc::ProfileKind::rail);
    set_track(w, rc::WheelsetTrack(profiles, parameters), "rc_wheelset_set_track_profiles");
  });
}

rc_status rc_wheelset_get_track(const rc_wheelset* w, rc_track_parameters* track, double* nominal_axle_height_m) {
  if (w == nullptr) return RC_INVALID_INPUT;
  return guarded(&w->error, [&] {
    if (!w->wheelset)
      throw Error("the wheelset has no track (rc_wheelset_set_default_track, rc_wheelset_set_track or "
                  "rc_wheelset_set_track_profiles first)");
    const rc::WheelsetTrack& t = w->wheelset->track();
    if (track != nullptr) {
      const rc::TrackWheelsetParameters& p = t.parameters();
      track->track_gauge_m = p.track_gauge_m;
      track->gauge_measuring_depth_m = p.gauge_measuring_depth_m;
      track->flange_back_distance_m = p.flange_back_distance_m;
      track->flange_back_y_m = p.flange_back_y_m;
      track->taping_line_from_flange_back_m = p.taping_line_from_flange_back_m;
      track->nominal_rolling_radius_m = p.nominal_rolling_radius_m;
      track->nominal_radius_at = datum_of(p.nominal_radius_at);
      track->rail_cant_rad = p.rail_cant_rad;
    }
    if (nominal_axle_height_m != nullptr) *nominal_axle_height_m = t.nominal_axle_height_m();
  });
}

rc_status rc_wheelset_set_options(rc_wheelset* w, const rc_wheelset_options* options) {
  if (w == nullptr) return RC_INVALID_INPUT;
  return guarded(&w->error, [&] {
    require_pointer(options, "rc_wheelset_set_options: options");
    rc::WheelsetOptions checked = options_of(*options);
    if (w->wheelset) {
      rc::Wheelset rebuilt(w->wheelset->track(), std::move(checked));
      w->wheelset.reset();
      w->wheelset.emplace(std::move(rebuilt));
    }
    w->options = *options;
    w->last.reset();
    recheck_table(w, "rc_wheelset_set_options");
  });
}

rc_status rc_wheelset_get_options(const rc_wheelset* w, rc_wheelset_options* options) {
  if (w == nullptr || options == nullptr) return RC_INVALID_INPUT;
  *options = w->options;
  return RC_OK;
}

namespace {

// With rc_wheelset_time_stages on: times one evaluation of `wheelset` and adds its stage times to
// the handle's when it ends, also by an exception.
class TimedEvaluation {
 public:
  TimedEvaluation(rc_wheelset& w, rc::Wheelset& wheelset) : w_(w), wheelset_(wheelset) {
    if (w_.time_stages) wheelset_.time_stages(true);
  }
  ~TimedEvaluation() {
    if (w_.time_stages) w_.stage_times += wheelset_.stage_times();
  }
  TimedEvaluation(const TimedEvaluation&) = delete;
  TimedEvaluation& operator=(const TimedEvaluation&) = delete;

 private:
  rc_wheelset& w_;
  rc::Wheelset& wheelset_;
};

}  // namespace

rc_status rc_wheelset_evaluate(rc_wheelset* w, const rc_wheelset_state* state, rc_wheelset_result* result) {
  if (w == nullptr) return RC_INVALID_INPUT;
  return guarded(&w->error, [&] {
    require_pointer(state, "rc_wheelset_evaluate: state");
    const rc::WheelsetState s = state_of(*state);
    rc::Wheelset& wheelset = require_wheelset(w);
    w->last.reset();
    if (w->options.warm_start == 0) wheelset = rc::Wheelset(wheelset);  // a copy starts cold
    const TimedEvaluation timed(*w, wheelset);
    w->last = wheelset.evaluate(s);
    if (result != nullptr) *result = result_of(*w->last);
  });
}

rc_status rc_wheelset_time_stages(rc_wheelset* w, int on) {
  if (w == nullptr) return RC_INVALID_INPUT;
  return guarded(&w->error, [&] {
    w->time_stages = on != 0;
    w->stage_times = {};
    if (w->wheelset) w->wheelset->time_stages(w->time_stages);
  });
}

rc_status rc_wheelset_stage_times_get(const rc_wheelset* w, rc_wheelset_stage_times* times) {
  if (w == nullptr) return RC_INVALID_INPUT;
  return guarded(&w->error, [&] {
    require_pointer(times, "rc_wheelset_stage_times_get: times");
    const rc::WheelsetStageTimes& t = w->stage_times;
    *times = rc_wheelset_stage_times{t.search_s,       t.area_s,       t.normal_s,   t.height_s,
                                     t.kinematics_s,   t.tangential_s, t.assembly_s, t.evaluations};
  });
}

rc_status rc_wheelset_reset_warm_start(rc_wheelset* w) {
  if (w == nullptr) return RC_INVALID_INPUT;
  return guarded(&w->error, [&] {
    if (w->wheelset) w->wheelset->reset_warm_start();
  });
}

rc_status rc_wheelset_result_get(const rc_wheelset* w, rc_wheelset_result* result) {
  if (w == nullptr) return RC_INVALID_INPUT;
  return guarded(&w->error, [&] {
    require_pointer(result, "rc_wheelset_result_get: result");
    *result = result_of(require_result(w));
  });
}

rc_status rc_wheelset_wheel_angular_velocity(const rc_wheelset* w, double* rad_per_s) {
  if (w == nullptr) return RC_INVALID_INPUT;
  return guarded(&w->error, [&] {
    require_pointer(rad_per_s, "rc_wheelset_wheel_angular_velocity: rad_per_s");
    const rc::WheelsetResult& r = require_result(w);
    const double r0 = w->wheelset ? w->wheelset->track().parameters().nominal_rolling_radius_m
                                  : w->table->nominal_rolling_radius_m();
    *rad_per_s = rc::wheelset_motion(r.state, r0).wheel_angular_velocity_rad_per_s;
  });
}

rc_status rc_wheelset_patch_count(const rc_wheelset* w, int side, size_t* count) {
  if (w == nullptr) return RC_INVALID_INPUT;
  return guarded(&w->error, [&] {
    require_pointer(count, "rc_wheelset_patch_count: count");
    const std::size_t k = side_index(side);
    *count = require_result(w).wheels[k].patches.size();
  });
}

rc_status rc_wheelset_patches(const rc_wheelset* w, int side, size_t size, rc_wheelset_patch* patches) {
  if (w == nullptr) return RC_INVALID_INPUT;
  return guarded(&w->error, [&] {
    const std::size_t k = side_index(side);
    const std::vector<rc::WheelsetPatch>& ps = require_result(w).wheels[k].patches;
    if (size < ps.size())
      throw StatusError{RC_BUFFER_TOO_SMALL,
                        fmt::format("rc_wheelset_patches: the buffer holds {} patches; the {} wheel has {} "
                                    "(rc_wheelset_patch_count)",
                                    size, k == 0 ? "right" : "left", ps.size())};
    if (!ps.empty()) require_pointer(patches, "rc_wheelset_patches: patches");
    for (std::size_t j = 0; j < ps.size(); ++j) patches[j] = patch_of(ps[j]);
  });
}

rc_status rc_wheelset_batch_evaluate(rc_wheelset* w, size_t count, const rc_wheelset_state* states, int threads,
                                     rc_wheelset_result* results, size_t patches_per_wheel, rc_wheelset_patch* patches,
                                     int* statuses) {
  if (w == nullptr) return RC_INVALID_INPUT;
  rc_status first_failure = RC_OK;
  const rc_status status = guarded(&w->error, [&] {
    if (count == 0) return;
    require(count <= RC_MAX_WHEELSET_BATCH_STATES, [&] {
      return fmt::format("rc_wheelset_batch_evaluate: count = {} states; at most RC_MAX_WHEELSET_BATCH_STATES = {}",
                         count, RC_MAX_WHEELSET_BATCH_STATES);
    });
    require(patches_per_wheel <= RC_MAX_PATCHES_PER_WHEEL, [&] {
      return fmt::format("rc_wheelset_batch_evaluate: patches_per_wheel = {}; at most RC_MAX_PATCHES_PER_WHEEL = {}",
                         patches_per_wheel, RC_MAX_PATCHES_PER_WHEEL);
    });
    require_pointer(states, "rc_wheelset_batch_evaluate: states");
    require_pointer(results, "rc_wheelset_batch_evaluate: results");
    if (patches_per_wheel > 0) require_pointer(patches, "rc_wheelset_batch_evaluate: patches");
    if (threads < 0) throw Error(fmt::format("rc_wheelset_batch_evaluate: threads = {} must be >= 0", threads));
    const rc::Wheelset& prototype = require_wheelset(w);
    std::size_t workers =
        threads == 0 ? std::max(1u, std::thread::hardware_concurrency()) : static_cast<std::size_t>(threads);
    workers = std::min({workers, count, std::size_t{1024}});
    std::vector<rc_status> state_status(count, RC_OK);
    std::vector<std::string> messages(count);
    const BatchJob job{&prototype, states, results, patches_per_wheel, patches_per_wheel > 0 ? patches : nullptr,
                       &state_status, &messages};
    const std::size_t chunk = (count + workers - 1) / workers;
    std::vector<std::thread> pool;
    for (std::size_t t = 1; t < workers && t * chunk < count; ++t)
      pool.emplace_back(run_batch_range, std::cref(job), t * chunk, std::min(count, (t + 1) * chunk));
    run_batch_range(job, 0, std::min(count, chunk));
    for (std::thread& t : pool) t.join();
    for (std::size_t k = 0; k < count; ++k) {
      if (statuses != nullptr) statuses[k] = state_status[k];
      if (state_status[k] != RC_OK && first_failure == RC_OK) {
        first_failure = state_status[k];
        w->error.set(fmt::format("state {}: {}", k, messages[k]).c_str());
      }
    }
  });
  return status != RC_OK ? status : first_failure;
}

rc_status rc_wheelset_table_build(rc_wheelset* w, const double* y_m, size_t y_count, const double* yaw_rad,
                                  size_t yaw_count, const double* loads_N, size_t load_count,
                                  rc_progress_callback progress, void* user_data) {
  if (w == nullptr) return RC_INVALID_INPUT;
  return guarded(&w->error, [&] {
    rc::WheelsetTableGrid grid;
    grid.y_m = finite_grid(y_m, y_count, "rc_wheelset_table_build: y_m");
    grid.yaw_rad = finite_grid(yaw_rad, yaw_count, "rc_wheelset_table_build: yaw_rad");
    grid.wheel_load_N = finite_grid(loads_N, load_count, "rc_wheelset_table_build: loads_N");
    require(grid.size() <= 20000, [&] {
      return fmt::format("rc_wheelset_table_build: {} x {} x {} = {} nodes; at most 20000", y_count, yaw_count,
                         load_count, grid.size());
    });
    rc::validate(grid);
    const rc::Wheelset& wheelset = require_wheelset(w);
    rc::WheelsetTableOptions options;
    options.wheelset = wheelset.options();
    options.refinement.lateral_force_fraction = w->table_refinement;
    rc::WheelsetTableProgressCallback callback;
    if (progress != nullptr)
      callback = [&](const rc::WheelsetTableProgress& p) {
        if (progress(p.nodes_done, p.nodes_total, user_data) != 0) throw TableBuildCancelled{};
      };
    try {
      rc::WheelsetTable built = rc::build_wheelset_table(wheelset.track(), grid, options, callback);
      w->table.reset();
      w->table.emplace(std::move(built));
      w->table_dropped.clear();
    } catch (const TableBuildCancelled&) {
      throw StatusError{RC_CANCELLED, "rc_wheelset_table_build: cancelled by the progress callback"};
    }
  });
}

rc_status rc_wheelset_table_set_refinement(rc_wheelset* w, double lateral_force_fraction) {
  if (w == nullptr) return RC_INVALID_INPUT;
  return guarded(&w->error, [&] {
    require(std::isfinite(lateral_force_fraction) && lateral_force_fraction >= 0.0 && lateral_force_fraction <= 1.0,
            [&] {
              return fmt::format("rc_wheelset_table_set_refinement: lateral_force_fraction = {:g} must lie in [0, 1] "
                                 "(a fraction of the wheel load; 0: no refinement)",
                                 lateral_force_fraction);
            });
    w->table_refinement = lateral_force_fraction;
  });
}

rc_status rc_wheelset_table_load(rc_wheelset* w, const char* path) {
  if (w == nullptr) return RC_INVALID_INPUT;
  return guarded(&w->error, [&] {
    require_pointer(path, "rc_wheelset_table_load: path");
    const rc::Wheelset& wheelset = require_wheelset(w);
    rc::WheelsetTable loaded = rc::load_wheelset_table(path);
    loaded.check_track(wheelset.track());
    const std::string misfit = table_misfit(loaded, wheelset);
    require(misfit.empty(), [&] {
      return fmt::format("rc_wheelset_table_load: the wheelset table {} was built for other options: {}", path, misfit);
    });
    w->table.reset();
    w->table.emplace(std::move(loaded));
    w->table_dropped.clear();
  });
}

rc_status rc_wheelset_table_save(const rc_wheelset* w, const char* path) {
  if (w == nullptr) return RC_INVALID_INPUT;
  return guarded(&w->error, [&] {
    require_pointer(path, "rc_wheelset_table_save: path");
    rc::save_wheelset_table(require_table(w), path);
  });
}

rc_status rc_wheelset_table_size(const rc_wheelset* w, size_t* y_count, size_t* yaw_count, size_t* load_count) {
  if (w == nullptr) return RC_INVALID_INPUT;
  return guarded(&w->error, [&] {
    const rc::WheelsetTableGrid& grid = require_table(w).grid();
    if (y_count != nullptr) *y_count = grid.y_m.size();
    if (yaw_count != nullptr) *yaw_count = grid.yaw_rad.size();
    if (load_count != nullptr) *load_count = grid.wheel_load_N.size();
  });
}

rc_status rc_wheelset_evaluate_table(rc_wheelset* w, const rc_wheelset_state* state, rc_wheelset_result* result) {
  if (w == nullptr) return RC_INVALID_INPUT;
  return guarded(&w->error, [&] {
    require_pointer(state, "rc_wheelset_evaluate_table: state");
    const rc::WheelsetState s = state_of(*state);
    const rc::WheelsetTable& table = require_table(w);
    require(state->roll_rad == 0.0, [&] {
      return fmt::format("rc_wheelset_evaluate_table: rc_wheelset_state.roll_rad = {} rad must be 0: the table's nodes "
                         "have zero roll (rc_wheelset_evaluate solves a rolled wheelset)",
                         state->roll_rad);
    });
    require(w->options.normal_mode == RC_WHEELSET_BY_LOAD,
            "rc_wheelset_evaluate_table: the wheels carry the loads of the options: normal_mode must be "
            "RC_WHEELSET_BY_LOAD");
    w->last.reset();
    w->last = table.evaluate(s, rc::WheelLoads{w->options.right_load_N, w->options.left_load_N, false},
                             w->options.friction_coefficient, w->options.tangential_in_balance != 0);
    if (result != nullptr) *result = result_of(*w->last);
  });
}

}  // extern "C"
