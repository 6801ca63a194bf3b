// railcontact._core: the Python extension of the package railcontact (docs/PYTHON.md), a thin
// pybind11 layer over the C API (railcontact/railcontact.h). The package's Python code
// (python/railcontact/__init__.py) builds the result classes and holds the docstrings. Every solve
// and every wheelset evaluation releases the GIL; a failed call raises the exception class of its
// status (railcontact._errors).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "railcontact/railcontact.h"

namespace py = pybind11;

namespace {

const char* exception_name(rc_status status) {
  switch (status) {
    case RC_INVALID_INPUT: return "InvalidInputError";
    case RC_NO_CONTACT: return "NoContactError";
    case RC_SEVERAL_PATCHES: return "SeveralPatchesError";
    case RC_NOT_CONVERGED: return "NotConvergedError";
    case RC_IO: return "RailcontactIOError";
    case RC_CANCELLED: return "CancelledError";
    default: return "InternalError";
  }
}

[[noreturn]] void raise(rc_status status, const std::string& message) {
  if (status == RC_OUT_OF_MEMORY) throw std::bad_alloc();
  const py::object cls = py::module_::import("railcontact._errors").attr(exception_name(status));
  PyErr_SetString(cls.ptr(), message.c_str());
  throw py::error_already_set();
}

template <class Handle, class LastError>
std::string last_error(const Handle* handle, LastError get) {
  std::size_t length = 0;
  get(handle, nullptr, 0, &length);
  std::string message(length + 1, '\0');
  get(handle, message.data(), message.size(), nullptr);
  message.resize(length);
  return message;
}

py::dict normal_dict(const rc_normal_result& n) {
  py::dict d;
  d["normal_force_N"] = n.normal_force_N;
  d["area_m2"] = n.area_m2;
  d["max_pressure_Pa"] = n.max_pressure_Pa;
  d["approach_m"] = n.approach_m;
  d["a_m"] = n.a_m;
  d["b_m"] = n.b_m;
  d["dx1_m"] = n.dx1_m;
  d["dx2_m"] = n.dx2_m;
  d["x1_first_m"] = n.x1_first_m;
  d["x2_first_m"] = n.x2_first_m;
  d["contact_angle_rad"] = n.contact_angle_rad;
  d["spin_per_m"] = n.spin_per_m;
  d["n1"] = n.n1;
  d["n2"] = n.n2;
  d["elements_in_contact"] = n.elements_in_contact;
  return d;
}

py::tuple forces_tuple(const rc_forces& f) { return py::make_tuple(f.F1_N, f.F2_N, f.M3_Nm, f.adhesion_fraction); }

using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

class FlexTable;

class Solver {
 public:
  Solver() {
    if (rc_solver_create(&handle_) != RC_OK) throw std::bad_alloc();
  }
  ~Solver() { rc_solver_destroy(handle_); }
  Solver(const Solver&) = delete;
  Solver& operator=(const Solver&) = delete;

  void check(rc_status status) const {
    if (status != RC_OK) raise(status, last_error(handle_, rc_solver_last_error));
  }

  py::dict settings() const {
    rc_settings s;
    rc_solver_get_settings(handle_, &s);
    py::dict d;
#define RC_FIELD(name) d[#name] = s.name
    RC_FIELD(youngs_modulus_Pa); RC_FIELD(poisson_ratio); RC_FIELD(friction_coefficient); RC_FIELD(mesh_value);
    RC_FIELD(bound_skew); RC_FIELD(collocation_offset); RC_FIELD(tolerance); RC_FIELD(krylov_tolerance);
    RC_FIELD(regularisation); RC_FIELD(normal_tolerance); RC_FIELD(jacobian_step_creepage);
    RC_FIELD(jacobian_step_spin_per_m); RC_FIELD(method); RC_FIELD(mesh_mode); RC_FIELD(flexibility_coarsening);
    RC_FIELD(slip_direction); RC_FIELD(max_newton_iterations); RC_FIELD(max_krylov_iterations); RC_FIELD(normal_max_iterations);
#undef RC_FIELD
    return d;
  }

  void set_settings(const py::dict& d) {
    rc_settings s;
    rc_solver_get_settings(handle_, &s);
    for (const auto& item : d) {
      const std::string key = py::str(item.first);
      const py::handle value = item.second;
#define RC_DOUBLE(name) if (key == #name) { s.name = value.cast<double>(); continue; }
#define RC_INT(name) if (key == #name) { s.name = value.cast<int>(); continue; }
      RC_DOUBLE(youngs_modulus_Pa) RC_DOUBLE(poisson_ratio) RC_DOUBLE(friction_coefficient) RC_DOUBLE(mesh_value)
      RC_DOUBLE(bound_skew) RC_DOUBLE(collocation_offset) RC_DOUBLE(tolerance) RC_DOUBLE(krylov_tolerance)
      RC_DOUBLE(regularisation) RC_DOUBLE(normal_tolerance) RC_DOUBLE(jacobian_step_creepage)
      RC_DOUBLE(jacobian_step_spin_per_m) RC_INT(method) RC_INT(mesh_mode) RC_INT(flexibility_coarsening)
      RC_INT(slip_direction) RC_INT(max_newton_iterations) RC_INT(max_krylov_iterations) RC_INT(normal_max_iterations)
#undef RC_DOUBLE
#undef RC_INT
      raise(RC_INVALID_INPUT, "unknown setting '" + key + "'");
    }
    check(rc_solver_set_settings(handle_, &s));
  }

  // approach: none for the patch's normal force, else the approach prescribed (m).
  void set_patch(const rc_patch& patch, std::optional<double> approach) {
    rc_status status;
    {
      py::gil_scoped_release release;
      status = approach ? rc_solver_set_patch_at_approach(handle_, &patch, *approach)
                        : rc_solver_set_patch(handle_, &patch);
    }
    check(status);
  }

  void set_ellipse(double a, double b, double F3, std::optional<double> approach) {
    rc_patch p{};
    p.kind = RC_GEOMETRY_ELLIPSE;
    p.a_m = a;
    p.b_m = b;
    p.normal_force_N = F3;
    set_patch(p, approach);
  }
  void set_hertz(double A, double B, double F3, std::optional<double> approach) {
    rc_patch p{};
    p.kind = RC_GEOMETRY_HERTZ;
    p.A_per_m = A;
    p.B_per_m = B;
    p.normal_force_N = F3;
    set_patch(p, approach);
  }
  void set_grid(const DoubleArray& h, double dx1, double dx2, double F3, std::optional<double> approach) {
    if (h.ndim() != 2) raise(RC_INVALID_INPUT, "h must be a 2-D array of shape (n2, n1): rows along X2, columns along X1");
    rc_patch p{};
    p.kind = RC_GEOMETRY_GRID;
    p.grid_n2 = static_cast<int>(h.shape(0));
    p.grid_n1 = static_cast<int>(h.shape(1));
    p.grid_dx1_m = dx1;
    p.grid_dx2_m = dx2;
    p.grid_h_m = h.data();
    p.normal_force_N = F3;
    set_patch(p, approach);
  }
  void set_flextable_patch(const FlexTable& table, double y, double Fz);

  py::dict normal() const {
    rc_normal_result n{};
    check(rc_solver_normal_result(handle_, &n));
    return normal_dict(n);
  }

  py::tuple solve(double xi, double eta, double phi) {
    const rc_creepage c{xi, eta, phi};
    rc_forces f{};
    rc_status status;
    {
      py::gil_scoped_release release;
      status = rc_solver_solve(handle_, &c, &f);
    }
    check(status);
    return forces_tuple(f);
  }

  py::tuple jacobian(double xi, double eta, double phi) {
    const rc_creepage c{xi, eta, phi};
    rc_forces f{};
    py::array_t<double> J({3, 3});
    double* j = J.mutable_data();
    rc_status status;
    {
      py::gil_scoped_release release;
      status = rc_solver_jacobian(handle_, &c, &f, j);
    }
    check(status);
    return py::make_tuple(forces_tuple(f), J);
  }

  py::dict tractions() const {
    int n1 = 0, n2 = 0;
    std::size_t count = 0;
    check(rc_solver_traction_size(handle_, &n1, &n2, &count));
    py::array_t<double> p1({n2, n1}), p2({n2, n1}), p3({n2, n1});
    py::array_t<int> slip({n2, n1});
    check(rc_solver_tractions(handle_, count, p1.mutable_data(), p2.mutable_data(), p3.mutable_data(),
                              slip.mutable_data()));
    py::dict d;
    d["p1_Pa"] = p1;
    d["p2_Pa"] = p2;
    d["p3_Pa"] = p3;
    d["slip"] = slip;
    return d;
  }

  // patches: (m, 3) rows [a, b, F3] (ellipse) or [A, B, F3] (hertz), m = 1 or N; creepages (N, 3).
  // Returns forces (N, 4), statuses (N,), jacobians (N, 3, 3) or None, the first error message.
  py::tuple batch(const DoubleArray& patches, int kind, const DoubleArray& creepages, int threads, bool with_jacobian) {
    if (creepages.ndim() != 2 || creepages.shape(1) != 3)
      raise(RC_INVALID_INPUT, "creepages must be an array of shape (N, 3): xi, eta, phi (1/m)");
    if (patches.ndim() != 2 || patches.shape(1) != 3)
      raise(RC_INVALID_INPUT, "patches must be an array of shape (N, 3) or (1, 3)");
    if (kind != RC_GEOMETRY_ELLIPSE && kind != RC_GEOMETRY_HERTZ)
      raise(RC_INVALID_INPUT, "a batch takes ellipse or hertz patches");
    const std::size_t count = static_cast<std::size_t>(creepages.shape(0));
    const std::size_t patch_count = static_cast<std::size_t>(patches.shape(0));
    std::vector<rc_patch> ps(patch_count);
    for (std::size_t k = 0; k < patch_count; ++k) {
      rc_patch& p = ps[k];
      p = rc_patch{};
      p.kind = kind;
      const double* row = patches.data() + 3 * k;
      if (kind == RC_GEOMETRY_ELLIPSE) {
        p.a_m = row[0];
        p.b_m = row[1];
      } else {
        p.A_per_m = row[0];
        p.B_per_m = row[1];
      }
      p.normal_force_N = row[2];
    }
    std::vector<rc_creepage> cs(count);
    std::memcpy(cs.data(), creepages.data(), count * sizeof(rc_creepage));
    std::vector<rc_forces> forces(count);
    py::array_t<int> statuses(static_cast<py::ssize_t>(count));
    std::optional<py::array_t<double>> jacobians;
    if (with_jacobian) jacobians.emplace(std::vector<py::ssize_t>{static_cast<py::ssize_t>(count), 3, 3});
    double* j = jacobians ? jacobians->mutable_data() : nullptr;
    int* st = statuses.mutable_data();
    rc_status status;
    {
      py::gil_scoped_release release;
      status = count == 0 ? RC_OK
                          : rc_batch_creep_forces(handle_, count, ps.data(), patch_count, cs.data(), threads,
                                                  forces.data(), nullptr, j, st);
    }
    std::string message;
    if (status != RC_OK) {
      message = last_error(handle_, rc_solver_last_error);
      // A failure of the call itself (not of a state) raises at once.
      bool any_state_failed = false;
      for (std::size_t k = 0; k < count; ++k) any_state_failed = any_state_failed || st[k] != RC_OK;
      if (!any_state_failed) raise(status, message);
    }
    py::array_t<double> out({static_cast<py::ssize_t>(count), py::ssize_t{4}});
    double* o = out.mutable_data();
    for (std::size_t k = 0; k < count; ++k) {
      const bool ok = st[k] == RC_OK;
      o[4 * k + 0] = ok ? forces[k].F1_N : NAN;
      o[4 * k + 1] = ok ? forces[k].F2_N : NAN;
      o[4 * k + 2] = ok ? forces[k].M3_Nm : NAN;
      o[4 * k + 3] = ok ? forces[k].adhesion_fraction : NAN;
    }
    return py::make_tuple(out, statuses, jacobians ? py::object(*jacobians) : py::object(py::none()),
                          py::make_tuple(static_cast<int>(status), message));
  }

  rc_solver* handle() const { return handle_; }

 private:
  rc_solver* handle_ = nullptr;
};

// A Python progress callback for a table build: progress(done, total) after each node; returning
// False stops the build (the C API then returns RC_CANCELLED); an exception it raises is kept and
// raised again after the build.
struct ProgressCallback {
  py::object callback;
  std::optional<py::error_already_set> error;
  static int call(std::size_t done, std::size_t total, void* user) {
    auto* c = static_cast<ProgressCallback*>(user);
    py::gil_scoped_acquire acquire;
    try {
      const py::object r = c->callback(done, total);
      return (!r.is_none() && r.cast<bool>() == false) ? 1 : 0;
    } catch (py::error_already_set& e) {
      c->error.emplace(std::move(e));
      return 1;
    }
  }
};

class FlexTable {
 public:
  FlexTable() {
    if (rc_flextable_create(&handle_) != RC_OK) throw std::bad_alloc();
  }
  ~FlexTable() { rc_flextable_destroy(handle_); }
  FlexTable(const FlexTable&) = delete;
  FlexTable& operator=(const FlexTable&) = delete;

  void check(rc_status status) const {
    if (status != RC_OK) raise(status, last_error(handle_, rc_flextable_last_error));
  }

  void load(const std::string& path, const std::optional<std::string>& setup) {
    rc_status status;
    {
      py::gil_scoped_release release;
      status = rc_flextable_load(handle_, path.c_str(), setup ? setup->c_str() : nullptr);
    }
    check(status);
  }

  void save(const std::string& path) const {
    rc_status status;
    {
      py::gil_scoped_release release;
      status = rc_flextable_save(handle_, path.c_str());
    }
    check(status);
  }

  void build(const std::optional<std::string>& setup, const DoubleArray& y, const DoubleArray& loads,
             int target_elements, double E, double nu, const py::object& progress) {
    ProgressCallback context{progress, std::nullopt};
    rc_status status;
    {
      py::gil_scoped_release release;
      status = rc_flextable_build(handle_, setup ? setup->c_str() : nullptr, y.data(), static_cast<std::size_t>(y.size()),
                                  loads.data(), static_cast<std::size_t>(loads.size()), target_elements, E, nu,
                                  progress.is_none() ? nullptr : &ProgressCallback::call, &context);
    }
    if (context.error) throw std::move(*context.error);
    check(status);
  }

  py::dict info() const {
    rc_flextable_info i{};
    check(rc_flextable_info_get(handle_, &i));
    py::dict d;
    d["y_min_m"] = i.y_min_m;
    d["y_max_m"] = i.y_max_m;
    d["load_min_N"] = i.load_min_N;
    d["load_max_N"] = i.load_max_N;
    d["youngs_modulus_Pa"] = i.youngs_modulus_Pa;
    d["poisson_ratio"] = i.poisson_ratio;
    d["y_count"] = i.y_count;
    d["load_count"] = i.load_count;
    d["target_elements"] = i.target_elements;
    return d;
  }

  py::dict lookup(double y, double Fz) const {
    rc_flextable_values v{};
    check(rc_flextable_lookup(handle_, y, Fz, &v));
    py::dict d;
    d["L1_m_per_Pa"] = v.L1_m_per_Pa;
    d["L2_m_per_Pa"] = v.L2_m_per_Pa;
    d["L3_m_per_Pa"] = v.L3_m_per_Pa;
    d["f11_N"] = v.f11_N;
    d["f22_N"] = v.f22_N;
    d["f23_Nm"] = v.f23_Nm;
    d["normal_force_N"] = v.normal_force_N;
    d["contact_angle_rad"] = v.contact_angle_rad;
    d["spin_per_m"] = v.spin_per_m;
    d["area_m2"] = v.area_m2;
    return d;
  }

  const rc_flextable* handle() const { return handle_; }

 private:
  rc_flextable* handle_ = nullptr;
};

void Solver::set_flextable_patch(const FlexTable& table, double y, double Fz) {
  rc_status status;
  {
    py::gil_scoped_release release;
    status = rc_solver_set_patch_flextable(handle_, table.handle(), y, Fz);
  }
  check(status);
}

py::array_t<double> vector3(const double v[3]) {
  py::array_t<double> a(3);
  std::memcpy(a.mutable_data(), v, 3 * sizeof(double));
  return a;
}

py::dict wheelset_patch_dict(const rc_wheelset_patch& p) {
  py::dict d;
  d["side"] = p.side == RC_WHEEL_RIGHT ? "right" : "left";
  d["reference_point_track_m"] = vector3(p.reference_point_track_m);
  d["x2_axis"] = vector3(p.x2_axis);
  d["x3_axis"] = vector3(p.x3_axis);
  d["contact_angle_rad"] = p.contact_angle_rad;
  d["rolling_radius_m"] = p.rolling_radius_m;
  d["max_interpenetration_m"] = p.max_interpenetration_m;
  d["xi"] = p.creepage.xi;
  d["eta"] = p.creepage.eta;
  d["phi_per_m"] = p.creepage.phi_per_m;
  d["normal_force_N"] = p.normal_force_N;
  d["area_m2"] = p.area_m2;
  d["max_pressure_Pa"] = p.max_pressure_Pa;
  d["pressure_centre_x1_m"] = p.pressure_centre_x1_m;
  d["pressure_centre_x2_m"] = p.pressure_centre_x2_m;
  d["elements_in_contact"] = p.elements_in_contact;
  d["normal_iterations"] = p.normal_iterations;
  py::list solvers;
  for (int k = 0; k < p.solver_count; ++k)
    solvers.append(py::make_tuple(p.forces[k].F1_N, p.forces[k].F2_N, p.forces[k].M3_Nm, p.forces[k].adhesion_fraction,
                                  vector3(p.force_track_N[k])));
  d["solvers"] = solvers;
  return d;
}

py::dict wheelset_result_dict(const rc_wheelset_result& r, const rc_wheelset_patch* patches, std::size_t per_wheel) {
  py::dict d;
  d["force_track_N"] = vector3(r.force_track_N);
  d["vertical_displacement_m"] = r.vertical_displacement_m;
  d["roll_rad"] = r.roll_rad;
  py::list wheels;
  for (int w = 0; w < 2; ++w) {
    py::dict wheel;
    wheel["side"] = w == RC_WHEEL_RIGHT ? "right" : "left";
    wheel["force_track_N"] = vector3(r.wheel_force_track_N[w]);
    wheel["vertical_displacement_m"] = r.wheel_vertical_displacement_m[w];
    wheel["load_iterations"] = r.load_iterations[w];
    py::list ps;
    for (int j = 0; j < r.patch_count[w]; ++j)
      ps.append(wheelset_patch_dict(patches[static_cast<std::size_t>(w) * per_wheel + static_cast<std::size_t>(j)]));
    wheel["patches"] = ps;
    wheels.append(wheel);
  }
  d["wheels"] = wheels;
  return d;
}

// A state from a row y, z, roll, yaw, V, vy, vz, roll rate, yaw rate, Omega (NaN: pure rolling),
// xi0 (docs/PYTHON.md "Wheelset").
constexpr int kStateColumns = 11;
rc_wheelset_state wheelset_state(const double* row) {
  rc_wheelset_state s;
  rc_wheelset_state_default(&s);
  s.y_m = row[0];
  s.z_m = row[1];
  s.roll_rad = row[2];
  s.yaw_rad = row[3];
  s.forward_speed_m_per_s = row[4];
  s.lateral_velocity_m_per_s = row[5];
  s.vertical_velocity_m_per_s = row[6];
  s.roll_rate_rad_per_s = row[7];
  s.yaw_rate_rad_per_s = row[8];
  s.rotation = std::isnan(row[9]) ? RC_ROTATION_ROLLING : RC_ROTATION_GIVEN;
  s.wheel_angular_velocity_rad_per_s = std::isnan(row[9]) ? 0.0 : row[9];
  s.extra_longitudinal_creepage = row[10];
  return s;
}

rc_track_parameters track_parameters(const py::dict& d) {
  rc_track_parameters t;
  rc_track_parameters_default(&t);
  for (const auto& item : d) {
    const std::string key = py::str(item.first);
    const double value = item.second.cast<double>();
    if (key == "track_gauge_m") t.track_gauge_m = value;
    else if (key == "gauge_measuring_depth_m") t.gauge_measuring_depth_m = value;
    else if (key == "flange_back_distance_m") t.flange_back_distance_m = value;
    else if (key == "flange_back_y_m") t.flange_back_y_m = value;
    else if (key == "taping_line_from_flange_back_m") t.taping_line_from_flange_back_m = value;
    else if (key == "nominal_rolling_radius_m") t.nominal_rolling_radius_m = value;
    else raise(RC_INVALID_INPUT, "unknown track parameter '" + key + "'");
  }
  return t;
}

class WheelsetHandle {
 public:
  WheelsetHandle() {
    if (rc_wheelset_create(&handle_) != RC_OK) throw std::bad_alloc();
  }
  ~WheelsetHandle() { rc_wheelset_destroy(handle_); }
  WheelsetHandle(const WheelsetHandle&) = delete;
  WheelsetHandle& operator=(const WheelsetHandle&) = delete;

  void check(rc_status status) const {
    if (status != RC_OK) raise(status, last_error(handle_, rc_wheelset_last_error));
  }

  void set_default_track() {
    rc_status status;
    {
      py::gil_scoped_release release;
      status = rc_wheelset_set_default_track(handle_);
    }
    check(status);
  }

  // paths: 2 (wheel, rail) or 4 (right wheel, left wheel, right rail, left rail).
  void set_track(const std::vector<std::string>& paths, const py::dict& dimensions) {
    const rc_track_parameters t = track_parameters(dimensions);
    if (paths.size() != 2 && paths.size() != 4) raise(RC_INVALID_INPUT, "2 or 4 profile paths are needed");
    rc_status status;
    {
      py::gil_scoped_release release;
      status = paths.size() == 2 ? rc_wheelset_set_track(handle_, paths[0].c_str(), paths[1].c_str(), &t)
                                 : rc_wheelset_set_track_profiles(handle_, paths[0].c_str(), paths[1].c_str(),
                                                                  paths[2].c_str(), paths[3].c_str(), &t);
    }
    check(status);
  }

  py::dict track() const {
    rc_track_parameters t{};
    double height = 0.0;
    check(rc_wheelset_get_track(handle_, &t, &height));
    py::dict d;
    d["track_gauge_m"] = t.track_gauge_m;
    d["gauge_measuring_depth_m"] = t.gauge_measuring_depth_m;
    d["flange_back_distance_m"] = t.flange_back_distance_m;
    d["flange_back_y_m"] = t.flange_back_y_m;
    d["taping_line_from_flange_back_m"] = t.taping_line_from_flange_back_m;
    d["nominal_rolling_radius_m"] = t.nominal_rolling_radius_m;
    d["nominal_axle_height_m"] = height;
    return d;
  }

  py::dict options() const {
    rc_wheelset_options o;
    rc_wheelset_get_options(handle_, &o);
    py::dict d;
#define RC_FIELD(name) d[#name] = o.name
    RC_FIELD(youngs_modulus_Pa); RC_FIELD(poisson_ratio); RC_FIELD(friction_coefficient); RC_FIELD(element_size_m);
    RC_FIELD(right_load_N); RC_FIELD(left_load_N); RC_FIELD(normal_mode); RC_FIELD(balance_roll);
    RC_FIELD(tangential_in_balance); RC_FIELD(allow_wheel_lift); RC_FIELD(warm_start); RC_FIELD(slip_direction);
#undef RC_FIELD
    py::list solvers;
    for (int k = 0; k < o.solver_count; ++k) solvers.append(o.solvers[k]);
    d["solvers"] = solvers;
    return d;
  }

  void set_options(const py::dict& d) {
    rc_wheelset_options o;
    rc_wheelset_get_options(handle_, &o);
    for (const auto& item : d) {
      const std::string key = py::str(item.first);
      const py::handle value = item.second;
#define RC_DOUBLE(name) if (key == #name) { o.name = value.cast<double>(); continue; }
#define RC_INT(name) if (key == #name) { o.name = value.cast<int>(); continue; }
      RC_DOUBLE(youngs_modulus_Pa) RC_DOUBLE(poisson_ratio) RC_DOUBLE(friction_coefficient) RC_DOUBLE(element_size_m)
      RC_DOUBLE(right_load_N) RC_DOUBLE(left_load_N) RC_INT(normal_mode) RC_INT(balance_roll)
      RC_INT(tangential_in_balance) RC_INT(allow_wheel_lift) RC_INT(warm_start) RC_INT(slip_direction)
#undef RC_DOUBLE
#undef RC_INT
      if (key == "solvers") {
        const auto solvers = value.cast<std::vector<int>>();
        if (solvers.empty() || solvers.size() > 4) raise(RC_INVALID_INPUT, "solvers: 1 to 4 tangential solvers");
        o.solver_count = static_cast<int>(solvers.size());
        for (std::size_t k = 0; k < solvers.size(); ++k) o.solvers[k] = solvers[k];
        continue;
      }
      raise(RC_INVALID_INPUT, "unknown wheelset option '" + key + "'");
    }
    check(rc_wheelset_set_options(handle_, &o));
  }

  void reset_warm_start() { check(rc_wheelset_reset_warm_start(handle_)); }

  py::dict evaluate(const DoubleArray& row) {
    if (row.ndim() != 1 || row.shape(0) != kStateColumns)
      raise(RC_INVALID_INPUT, "a wheelset state has 11 values");
    const rc_wheelset_state s = wheelset_state(row.data());
    rc_wheelset_result r{};
    rc_status status;
    {
      py::gil_scoped_release release;
      status = rc_wheelset_evaluate(handle_, &s, &r);
    }
    check(status);
    return result_with_patches(r);
  }

  // states (N, 11). Returns a list of result dicts (None for a failed state), the statuses, and
  // the first failure (status, message).
  py::tuple batch(const DoubleArray& states, int threads) {
    if (states.ndim() != 2 || states.shape(1) != kStateColumns)
      raise(RC_INVALID_INPUT, "states must be an array of shape (N, 11)");
    const std::size_t count = static_cast<std::size_t>(states.shape(0));
    std::vector<rc_wheelset_state> cs(count);
    for (std::size_t k = 0; k < count; ++k) cs[k] = wheelset_state(states.data() + kStateColumns * k);
    std::vector<rc_wheelset_result> results(count);
    std::vector<int> statuses(count, RC_OK);
    std::size_t per_wheel = 4;
    std::vector<rc_wheelset_patch> patches;
    rc_status status = RC_OK;
    for (int attempt = 0; attempt < 2; ++attempt) {
      patches.assign(2 * count * per_wheel, rc_wheelset_patch{});
      {
        py::gil_scoped_release release;
        status = count == 0 ? RC_OK
                            : rc_wheelset_batch_evaluate(handle_, count, cs.data(), threads, results.data(), per_wheel,
                                                         patches.data(), statuses.data());
      }
      std::size_t needed = 0;
      for (std::size_t k = 0; k < count; ++k)
        if (statuses[k] == RC_BUFFER_TOO_SMALL)
          needed = std::max({needed, static_cast<std::size_t>(results[k].patch_count[0]),
                             static_cast<std::size_t>(results[k].patch_count[1])});
      if (needed == 0) break;
      per_wheel = needed;  // again with room for every patch
    }
    std::string message;
    if (status != RC_OK) {
      message = last_error(handle_, rc_wheelset_last_error);
      bool any_state_failed = false;
      for (std::size_t k = 0; k < count; ++k) any_state_failed = any_state_failed || statuses[k] != RC_OK;
      if (!any_state_failed) raise(status, message);
    }
    py::list out;
    for (std::size_t k = 0; k < count; ++k) {
      if (statuses[k] != RC_OK)
        out.append(py::none());
      else
        out.append(wheelset_result_dict(results[k], patches.data() + 2 * k * per_wheel, per_wheel));
    }
    return py::make_tuple(out, statuses, py::make_tuple(static_cast<int>(status), message));
  }

  // The wheelset table (docs/WHEELSET_TABLE.md).
  void build_table(const DoubleArray& y, const DoubleArray& yaw, const DoubleArray& loads, const py::object& progress) {
    ProgressCallback context{progress, std::nullopt};
    rc_status status;
    {
      py::gil_scoped_release release;
      status = rc_wheelset_table_build(handle_, y.data(), static_cast<std::size_t>(y.size()), yaw.data(),
                                       static_cast<std::size_t>(yaw.size()), loads.data(),
                                       static_cast<std::size_t>(loads.size()), progress.is_none() ? nullptr : &ProgressCallback::call,
                                       &context);
    }
    if (context.error) throw std::move(*context.error);
    check(status);
  }

  void load_table(const std::string& path) {
    rc_status status;
    {
      py::gil_scoped_release release;
      status = rc_wheelset_table_load(handle_, path.c_str());
    }
    check(status);
  }

  void save_table(const std::string& path) const { check(rc_wheelset_table_save(handle_, path.c_str())); }

  py::dict evaluate_table(const DoubleArray& row) {
    if (row.ndim() != 1 || row.shape(0) != kStateColumns) raise(RC_INVALID_INPUT, "a wheelset state has 11 values");
    const rc_wheelset_state s = wheelset_state(row.data());
    rc_wheelset_result r{};
    check(rc_wheelset_evaluate_table(handle_, &s, &r));
    return result_with_patches(r);
  }

  // The fast path of a simulation step: [Fx, Fy, Fz of the right wheel, of the left wheel (track
  // frame, N), Mz about the wheelset centre (N m)] from the table, without building result objects.
  py::array_t<double> table_forces(const DoubleArray& row) {
    if (row.ndim() != 1 || row.shape(0) != kStateColumns) raise(RC_INVALID_INPUT, "a wheelset state has 11 values");
    const rc_wheelset_state s = wheelset_state(row.data());
    rc_wheelset_result r{};
    check(rc_wheelset_evaluate_table(handle_, &s, &r));
    py::array_t<double> out(7);
    double* f = out.mutable_data();
    double yaw_moment = 0.0;
    for (int w = 0; w < 2; ++w) {
      for (int i = 0; i < 3; ++i) f[3 * w + i] = r.wheel_force_track_N[w][i];
      rc_wheelset_patch patch[8];
      const std::size_t n = std::min<std::size_t>(static_cast<std::size_t>(r.patch_count[w]), 8);
      check(rc_wheelset_patches(handle_, w, 8, patch));
      for (std::size_t j = 0; j < n; ++j) {
        const double rx = patch[j].reference_point_track_m[0], ry = patch[j].reference_point_track_m[1] - s.y_m;
        yaw_moment += rx * patch[j].force_track_N[0][1] - ry * patch[j].force_track_N[0][0];
      }
    }
    f[6] = yaw_moment;
    return out;
  }

 private:
  // The totals of the last evaluation with both wheels' patches, as a dict.
  py::dict result_with_patches(const rc_wheelset_result& r) const {
    std::vector<rc_wheelset_patch> patches;
    std::size_t per_wheel = 0;
    for (int w = 0; w < 2; ++w) per_wheel = std::max(per_wheel, static_cast<std::size_t>(r.patch_count[w]));
    patches.resize(2 * per_wheel);
    for (int w = 0; w < 2; ++w)
      check(rc_wheelset_patches(handle_, w, per_wheel, patches.data() + static_cast<std::size_t>(w) * per_wheel));
    return wheelset_result_dict(r, patches.data(), per_wheel);
  }

  rc_wheelset* handle_ = nullptr;
};

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "railcontact's extension module (use the package railcontact, docs/PYTHON.md)";
  m.def("version_string", [] { return std::string(rc_version_string()); });
  m.def("abi_version", [] { return rc_abi_version(); });
  m.def("status_string", [](int status) { return std::string(rc_status_string(status)); });

  py::class_<Solver>(m, "Solver")
      .def(py::init<>())
      .def("settings", &Solver::settings)
      .def("set_settings", &Solver::set_settings)
      .def("set_ellipse", &Solver::set_ellipse)
      .def("set_hertz", &Solver::set_hertz)
      .def("set_grid", &Solver::set_grid)
      .def("set_flextable_patch", &Solver::set_flextable_patch)
      .def("normal", &Solver::normal)
      .def("solve", &Solver::solve)
      .def("jacobian", &Solver::jacobian)
      .def("tractions", &Solver::tractions)
      .def("batch", &Solver::batch);

  py::class_<WheelsetHandle>(m, "Wheelset")
      .def(py::init<>())
      .def("set_default_track", &WheelsetHandle::set_default_track)
      .def("set_track", &WheelsetHandle::set_track)
      .def("track", &WheelsetHandle::track)
      .def("options", &WheelsetHandle::options)
      .def("set_options", &WheelsetHandle::set_options)
      .def("evaluate", &WheelsetHandle::evaluate)
      .def("reset_warm_start", &WheelsetHandle::reset_warm_start)
      .def("batch", &WheelsetHandle::batch)
      .def("build_table", &WheelsetHandle::build_table)
      .def("load_table", &WheelsetHandle::load_table)
      .def("save_table", &WheelsetHandle::save_table)
      .def("evaluate_table", &WheelsetHandle::evaluate_table)
      .def("table_forces", &WheelsetHandle::table_forces);

  py::class_<FlexTable>(m, "FlexTable")
      .def(py::init<>())
      .def("load", &FlexTable::load)
      .def("save", &FlexTable::save)
      .def("build", &FlexTable::build)
      .def("info", &FlexTable::info)
      .def("lookup", &FlexTable::lookup);
}
