// railcontact._core: the Python extension of the package railcontact (docs/PYTHON.md), a thin
// pybind11 layer over the C API (railcontact/railcontact.h). The package's Python code
// (python/railcontact/__init__.py) builds the result classes, checks the arguments and holds the
// docstrings. A failed call raises the exception class of its status (railcontact._errors).
//
// Threads: a C handle is used by one thread at a time (docs/C_API.md "Threads"), but Python code
// may share one object between threads. Each object wrapping a handle therefore has its own
// HandleLock, held by every call that touches the handle, and every such call runs with the GIL
// released, so that other threads run meanwhile. The lock is taken only with the GIL released:
// a thread waiting for it holds no GIL, so its holder may take the GIL back (a progress
// callback) without a deadlock. A call reads its results and its error message under the lock
// and builds the Python objects after it.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <mutex>
#include <optional>
#include <shared_mutex>
#include <string>
#include <thread>
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

// A call's status with the handle's message, read under the handle's lock and raised after it.
struct Outcome {
  rc_status status = RC_OK;
  std::string message;
  void raise_if_failed() const {
    if (status != RC_OK) raise(status, message);
  }
};

// The lock of one object wrapping a C handle (see the top of this file). exclusive(f) runs f with
// the GIL released, holding the lock; f touches no Python object (a progress callback takes the
// GIL itself). A call from a progress callback into the object whose build it reports on would
// wait for itself: it raises InvalidInputError instead.
class HandleLock {
 public:
  template <class F>
  auto exclusive(const char* object, F&& f) {
    refuse_reentry(object);
    py::gil_scoped_release release;
    std::unique_lock<std::shared_mutex> lock(mutex_);
    const Owner owner(owner_);
    return f();
  }

  // For another object's call that only reads this one (a solver's patch from a flexibility
  // table): with the GIL released, under that object's lock. Several readers share it.
  std::shared_lock<std::shared_mutex> shared() { return std::shared_lock<std::shared_mutex>(mutex_); }

  // With the GIL held: raises when this thread holds the lock already.
  void refuse_reentry(const char* object) const {
    if (owner_.load() == std::this_thread::get_id())
      raise(RC_INVALID_INPUT, std::string("this ") + object +
                                  " is busy with a call on this thread (a progress callback cannot use the object "
                                  "whose build it reports on)");
  }

 private:
  struct Owner {
    std::atomic<std::thread::id>& id;
    explicit Owner(std::atomic<std::thread::id>& owner) : id(owner) { id = std::this_thread::get_id(); }
    ~Owner() { id = std::thread::id(); }
    Owner(const Owner&) = delete;
    Owner& operator=(const Owner&) = delete;
  };
  std::shared_mutex mutex_;
  std::atomic<std::thread::id> owner_{};
};

// A number of a settings or options dict (the package checks the types; this keeps a wrong type
// from the private module a TypeError too).
double number_of(const std::string& key, const py::handle& value) {
  if (py::isinstance<py::bool_>(value) || !(py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value)))
    throw py::type_error("'" + key + "' must be a number (got " + std::string(py::str(py::type::of(value).attr("__name__"))) + ")");
  return value.cast<double>();
}

class FlexTable;

// The settings of rc_settings by name: the dict of Solver.settings and of set_settings.
#define RC_SETTINGS_DOUBLES(X)                                                                                         \
  X(youngs_modulus_Pa) X(poisson_ratio) X(friction_coefficient) X(mesh_value) X(bound_skew) X(collocation_offset)       \
  X(tolerance) X(krylov_tolerance) X(regularisation) X(normal_tolerance) X(jacobian_step_creepage)                     \
  X(jacobian_step_spin_per_m)
#define RC_SETTINGS_INTS(X)                                                                                            \
  X(method) X(mesh_mode) X(flexibility_coarsening) X(slip_direction) X(max_newton_iterations) X(max_krylov_iterations) \
  X(normal_max_iterations)

// Sets the field `key` of s to value; false for an unknown key.
bool assign_setting(rc_settings& s, const std::string& key, double value) {
#define RC_DOUBLE(name) if (key == #name) { s.name = value; return true; }
#define RC_INT(name) if (key == #name) { s.name = static_cast<int>(value); return true; }
  RC_SETTINGS_DOUBLES(RC_DOUBLE) RC_SETTINGS_INTS(RC_INT)
#undef RC_DOUBLE
#undef RC_INT
  return false;
}

class Solver {
 public:
  Solver() {
    if (rc_solver_create(&handle_) != RC_OK) throw std::bad_alloc();
  }
  ~Solver() { rc_solver_destroy(handle_); }
  Solver(const Solver&) = delete;
  Solver& operator=(const Solver&) = delete;

  py::dict settings() {
    rc_settings s;
    lock_.exclusive("Solver", [&] { rc_solver_get_settings(handle_, &s); });
    py::dict d;
#define RC_FIELD(name) d[#name] = s.name;
    RC_SETTINGS_DOUBLES(RC_FIELD) RC_SETTINGS_INTS(RC_FIELD)
#undef RC_FIELD
    return d;
  }

  void set_settings(const py::dict& d) {
    std::vector<std::pair<std::string, double>> values;
    for (const auto& item : d) {
      const std::string key = py::str(item.first);
      rc_settings probe{};
      if (!assign_setting(probe, key, 0.0)) raise(RC_INVALID_INPUT, "unknown setting '" + key + "'");
      values.emplace_back(key, number_of(key, item.second));
    }
    lock_.exclusive("Solver", [&] {
      rc_settings s;
      rc_solver_get_settings(handle_, &s);
      for (const auto& [key, value] : values) assign_setting(s, key, value);
      ++serial_;  // a changed material, mesh or method discards the patch
      return outcome(rc_solver_set_settings(handle_, &s));
    }).raise_if_failed();
  }

  // approach: none for the patch's normal force, else the approach prescribed (m). Returns the
  // patch's serial number and its normal results.
  py::tuple set_patch(const rc_patch& patch, std::optional<double> approach) {
    rc_normal_result n{};
    std::uint64_t serial = 0;
    lock_.exclusive("Solver", [&] {
      serial = ++serial_;
      batch_patch_.reset();
      rc_status status = approach ? rc_solver_set_patch_at_approach(handle_, &patch, *approach)
                                  : rc_solver_set_patch(handle_, &patch);
      if (status == RC_OK) status = rc_solver_normal_result(handle_, &n);
      if (status == RC_OK && !approach && (patch.kind == RC_GEOMETRY_ELLIPSE || patch.kind == RC_GEOMETRY_HERTZ))
        batch_patch_ = patch;
      return outcome(status);
    }).raise_if_failed();
    return py::make_tuple(serial, normal_dict(n));
  }

  py::tuple set_ellipse(double a, double b, double F3, std::optional<double> approach) {
    rc_patch p{};
    p.kind = RC_GEOMETRY_ELLIPSE;
    p.a_m = a;
    p.b_m = b;
    p.normal_force_N = F3;
    return set_patch(p, approach);
  }
  py::tuple set_hertz(double A, double B, double F3, std::optional<double> approach) {
    rc_patch p{};
    p.kind = RC_GEOMETRY_HERTZ;
    p.A_per_m = A;
    p.B_per_m = B;
    p.normal_force_N = F3;
    return set_patch(p, approach);
  }
  py::tuple set_grid(const DoubleArray& h, double dx1, double dx2, double F3, std::optional<double> approach) {
    if (h.ndim() != 2) raise(RC_INVALID_INPUT, "h must be a 2-D array of shape (n2, n1): rows along X2, columns along X1");
    rc_patch p{};
    p.kind = RC_GEOMETRY_GRID;
    p.grid_n2 = static_cast<int>(h.shape(0));
    p.grid_n1 = static_cast<int>(h.shape(1));
    p.grid_dx1_m = dx1;
    p.grid_dx2_m = dx2;
    p.grid_h_m = h.data();
    p.normal_force_N = F3;
    return set_patch(p, approach);
  }
  py::tuple set_flextable_patch(FlexTable& table, double y, double Fz);

  // The patch's serial number and its normal results.
  py::tuple normal() {
    rc_normal_result n{};
    std::uint64_t serial = 0;
    lock_.exclusive("Solver", [&] {
      serial = serial_;
      return outcome(rc_solver_normal_result(handle_, &n));
    }).raise_if_failed();
    return py::make_tuple(serial, normal_dict(n));
  }

  // One solve, with the traction fields and the Jacobian when asked for, all of the same patch:
  // (forces, J or None, tractions dict or None, the patch's serial number, its normal results or
  // None when known_serial is that number).
  py::tuple solve(double xi, double eta, double phi, bool with_tractions, bool with_jacobian, std::uint64_t known_serial) {
    const rc_creepage c{xi, eta, phi};
    rc_forces f{};
    double J[9] = {};
    int n1 = 0, n2 = 0;
    std::vector<double> p1, p2, p3;
    std::vector<int> slip;
    rc_normal_result n{};
    std::uint64_t serial = 0;
    lock_.exclusive("Solver", [&] {
      rc_status status = with_jacobian ? rc_solver_jacobian(handle_, &c, &f, J) : rc_solver_solve(handle_, &c, &f);
      if (status == RC_OK && with_tractions) {
        std::size_t count = 0;
        status = rc_solver_traction_size(handle_, &n1, &n2, &count);
        if (status == RC_OK) {
          p1.resize(count);
          p2.resize(count);
          p3.resize(count);
          slip.resize(count);
          status = rc_solver_tractions(handle_, count, p1.data(), p2.data(), p3.data(), slip.data());
        }
      }
      serial = serial_;
      if (status == RC_OK && serial != known_serial) status = rc_solver_normal_result(handle_, &n);
      return outcome(status);
    }).raise_if_failed();
    py::object jacobian = py::none(), tractions = py::none(), normal = py::none();
    if (with_jacobian) {
      py::array_t<double> a({3, 3});
      std::memcpy(a.mutable_data(), J, sizeof J);
      jacobian = a;
    }
    if (with_tractions) {
      const auto field = [&](const auto& v) {
        py::array_t<typename std::decay_t<decltype(v)>::value_type> a({n2, n1});
        if (!v.empty()) std::memcpy(a.mutable_data(), v.data(), v.size() * sizeof v[0]);
        return a;
      };
      py::dict d;
      d["p1_Pa"] = field(p1);
      d["p2_Pa"] = field(p2);
      d["p3_Pa"] = field(p3);
      d["slip"] = field(slip);
      tractions = d;
    }
    if (serial != known_serial) normal = normal_dict(n);
    return py::make_tuple(forces_tuple(f), jacobian, tractions, serial, normal);
  }

  // patches: (m, 3) rows [a, b, F3] (ellipse) or [A, B, F3] (hertz), m = 1 or N, or None for the
  // patch set (an ellipse or Hertz patch given its force); creepages (N, 3). Returns forces
  // (N, 4), statuses (N,), jacobians (N, 3, 3) or None, the first error (status, message).
  py::tuple batch(const std::optional<DoubleArray>& patches, int kind, const DoubleArray& creepages, int threads,
                  bool with_jacobian) {
    if (creepages.ndim() != 2 || creepages.shape(1) != 3)
      raise(RC_INVALID_INPUT, "creepages must be an array of shape (N, 3): xi, eta, phi (1/m)");
    const std::size_t count = static_cast<std::size_t>(creepages.shape(0));
    std::vector<rc_patch> ps;
    if (patches) {
      if (patches->ndim() != 2 || patches->shape(1) != 3 ||
          (patches->shape(0) != 1 && static_cast<std::size_t>(patches->shape(0)) != count))
        raise(RC_INVALID_INPUT, "patches must be an array of shape (N, 3) or (1, 3), N the number of creepages");
      if (kind != RC_GEOMETRY_ELLIPSE && kind != RC_GEOMETRY_HERTZ)
        raise(RC_INVALID_INPUT, "a batch takes ellipse or hertz patches");
      ps.resize(static_cast<std::size_t>(patches->shape(0)));
      for (std::size_t k = 0; k < ps.size(); ++k) {
        rc_patch& p = ps[k];
        p = rc_patch{};
        p.kind = kind;
        const double* row = patches->data() + 3 * k;
        if (kind == RC_GEOMETRY_ELLIPSE) {
          p.a_m = row[0];
          p.b_m = row[1];
        } else {
          p.A_per_m = row[0];
          p.B_per_m = row[1];
        }
        p.normal_force_N = row[2];
      }
    }
    std::vector<rc_creepage> cs(count);
    if (count > 0) std::memcpy(cs.data(), creepages.data(), count * sizeof(rc_creepage));
    std::vector<rc_forces> forces(count);
    py::array_t<int> statuses(static_cast<py::ssize_t>(count));
    std::optional<py::array_t<double>> jacobians;
    if (with_jacobian) jacobians.emplace(std::vector<py::ssize_t>{static_cast<py::ssize_t>(count), 3, 3});
    double* j = jacobians ? jacobians->mutable_data() : nullptr;
    int* st = statuses.mutable_data();
    const Outcome result = lock_.exclusive("Solver", [&] {
      if (!patches && !batch_patch_)
        return Outcome{RC_INVALID_INPUT, "batch without patches= uses the patch of set_ellipse or set_hertz given "
                                         "its normal force; none set"};
      if (!patches) ps.assign(1, *batch_patch_);
      if (count == 0) return Outcome{};
      return outcome(rc_batch_creep_forces(handle_, count, ps.data(), ps.size(), cs.data(), threads, forces.data(),
                                           nullptr, j, st));
    });
    if (result.status != RC_OK) {
      // A failure of the call itself (not of a state) raises at once.
      bool any_state_failed = false;
      for (std::size_t k = 0; k < count; ++k) any_state_failed = any_state_failed || st[k] != RC_OK;
      if (!any_state_failed) result.raise_if_failed();
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
                          py::make_tuple(static_cast<int>(result.status), result.message));
  }

 private:
  // Under the lock: the status with the solver's message.
  Outcome outcome(rc_status status) const {
    return status == RC_OK ? Outcome{} : Outcome{status, last_error(handle_, rc_solver_last_error)};
  }

  HandleLock lock_;
  rc_solver* handle_ = nullptr;
  std::uint64_t serial_ = 0;             // counts the patches set (and settings that may discard one)
  std::optional<rc_patch> batch_patch_;  // the ellipse or Hertz patch given its force, for batch()
};

// A Python progress callback for a table build: progress(done, total) after each node; returning
// False stops the build (the C API then returns RC_CANCELLED); an exception it raises is kept and
// raised again after the build. Called on the building thread, which holds the object's lock
// but not the GIL.
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

  void load(const std::string& path, const std::optional<std::string>& setup) {
    lock_.exclusive("FlexibilityTable", [&] {
      return outcome(rc_flextable_load(handle_, path.c_str(), setup ? setup->c_str() : nullptr));
    }).raise_if_failed();
  }

  void save(const std::string& path) {
    lock_.exclusive("FlexibilityTable", [&] { return outcome(rc_flextable_save(handle_, path.c_str())); })
        .raise_if_failed();
  }

  void build(const std::optional<std::string>& setup, const DoubleArray& y, const DoubleArray& loads,
             int target_elements, double E, double nu, const py::object& progress) {
    ProgressCallback context{progress, std::nullopt};
    const Outcome result = lock_.exclusive("FlexibilityTable", [&] {
      return outcome(rc_flextable_build(handle_, setup ? setup->c_str() : nullptr, y.data(),
                                        static_cast<std::size_t>(y.size()), loads.data(),
                                        static_cast<std::size_t>(loads.size()), target_elements, E, nu,
                                        progress.is_none() ? nullptr : &ProgressCallback::call, &context));
    });
    if (context.error) throw std::move(*context.error);
    result.raise_if_failed();
  }

  py::dict info() {
    rc_flextable_info i{};
    lock_.exclusive("FlexibilityTable", [&] { return outcome(rc_flextable_info_get(handle_, &i)); }).raise_if_failed();
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

  py::dict lookup(double y, double Fz) {
    rc_flextable_values v{};
    lock_.exclusive("FlexibilityTable", [&] { return outcome(rc_flextable_lookup(handle_, y, Fz, &v)); })
        .raise_if_failed();
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

 private:
  friend class Solver;
  Outcome outcome(rc_status status) const {
    return status == RC_OK ? Outcome{} : Outcome{status, last_error(handle_, rc_flextable_last_error)};
  }

  HandleLock lock_;
  rc_flextable* handle_ = nullptr;
};

py::tuple Solver::set_flextable_patch(FlexTable& table, double y, double Fz) {
  table.lock_.refuse_reentry("FlexibilityTable");
  rc_normal_result n{};
  std::uint64_t serial = 0;
  lock_.exclusive("Solver", [&] {
    const auto reading = table.lock_.shared();  // solvers on several threads may read one table
    serial = ++serial_;
    batch_patch_.reset();
    rc_status status = rc_solver_set_patch_flextable(handle_, table.handle_, y, Fz);
    if (status == RC_OK) status = rc_solver_normal_result(handle_, &n);
    return outcome(status);
  }).raise_if_failed();
  return py::make_tuple(serial, normal_dict(n));
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
  d["pressure_force_track_N"] = vector3(p.pressure_force_track_N);
  d["contact_angle_spread_rad"] = p.contact_angle_spread_rad;
  d["conformal_weight"] = p.conformal_weight;
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
rc_wheelset_state wheelset_state(const double* row, bool free_rolling_mark = false) {
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
  // The angular velocity column: NaN pure rolling; with free_rolling_mark (evaluate(...,
  // free_rolling=True), whose user values are checked finite first) +inf free rolling; else the
  // value (a batch's infinity is refused by the C API as any other).
  const bool free = free_rolling_mark && std::isinf(row[9]) && row[9] > 0.0;
  s.rotation = std::isnan(row[9]) ? RC_ROTATION_ROLLING : free ? RC_ROTATION_FREE : RC_ROTATION_GIVEN;
  s.wheel_angular_velocity_rad_per_s = std::isnan(row[9]) || free ? 0.0 : row[9];
  s.extra_longitudinal_creepage = row[10];
  return s;
}

rc_track_parameters track_parameters(const py::dict& d) {
  rc_track_parameters t;
  rc_track_parameters_default(&t);
  for (const auto& item : d) {
    const std::string key = py::str(item.first);
    const double value = number_of(key, item.second);
    if (key == "track_gauge_m") t.track_gauge_m = value;
    else if (key == "gauge_measuring_depth_m") t.gauge_measuring_depth_m = value;
    else if (key == "flange_back_distance_m") t.flange_back_distance_m = value;
    else if (key == "flange_back_y_m") t.flange_back_y_m = value;
    else if (key == "taping_line_from_flange_back_m") t.taping_line_from_flange_back_m = value;
    else if (key == "nominal_rolling_radius_m") t.nominal_rolling_radius_m = value;
    else if (key == "nominal_radius_at") t.nominal_radius_at = static_cast<int>(value);
    else if (key == "rail_cant_rad") t.rail_cant_rad = value;
    else raise(RC_INVALID_INPUT, "unknown track parameter '" + key + "'");
  }
  return t;
}

#define RC_WHEELSET_DOUBLES(X) \
  X(youngs_modulus_Pa) X(poisson_ratio) X(friction_coefficient) X(element_size_m) X(right_load_N) X(left_load_N)
#define RC_WHEELSET_INTS(X) \
  X(normal_mode) X(balance_roll) X(tangential_in_balance) X(allow_wheel_lift) X(warm_start) X(slip_direction) \
      X(balance_solver) X(reference_weighting) X(contact_surface)

bool assign_option(rc_wheelset_options& o, const std::string& key, double value) {
#define RC_DOUBLE(name) if (key == #name) { o.name = value; return true; }
#define RC_INT(name) if (key == #name) { o.name = static_cast<int>(value); return true; }
  RC_WHEELSET_DOUBLES(RC_DOUBLE) RC_WHEELSET_INTS(RC_INT)
#undef RC_DOUBLE
#undef RC_INT
  return false;
}

class WheelsetHandle {
 public:
  WheelsetHandle() {
    if (rc_wheelset_create(&handle_) != RC_OK) throw std::bad_alloc();
  }
  ~WheelsetHandle() { rc_wheelset_destroy(handle_); }
  WheelsetHandle(const WheelsetHandle&) = delete;
  WheelsetHandle& operator=(const WheelsetHandle&) = delete;

  void set_default_track() {
    lock_.exclusive("Wheelset", [&] { return outcome(rc_wheelset_set_default_track(handle_)); }).raise_if_failed();
  }

  // paths: 2 (wheel, rail) or 4 (right wheel, left wheel, right rail, left rail).
  void set_track(const std::vector<std::string>& paths, const py::dict& dimensions) {
    const rc_track_parameters t = track_parameters(dimensions);
    if (paths.size() != 2 && paths.size() != 4) raise(RC_INVALID_INPUT, "2 or 4 profile paths are needed");
    lock_.exclusive("Wheelset", [&] {
      return outcome(paths.size() == 2 ? rc_wheelset_set_track(handle_, paths[0].c_str(), paths[1].c_str(), &t)
                                       : rc_wheelset_set_track_profiles(handle_, paths[0].c_str(), paths[1].c_str(),
                                                                        paths[2].c_str(), paths[3].c_str(), &t));
    }).raise_if_failed();
  }

  py::dict track() {
    rc_track_parameters t{};
    double height = 0.0;
    lock_.exclusive("Wheelset", [&] { return outcome(rc_wheelset_get_track(handle_, &t, &height)); }).raise_if_failed();
    py::dict d;
    d["track_gauge_m"] = t.track_gauge_m;
    d["gauge_measuring_depth_m"] = t.gauge_measuring_depth_m;
    d["flange_back_distance_m"] = t.flange_back_distance_m;
    d["flange_back_y_m"] = t.flange_back_y_m;
    d["taping_line_from_flange_back_m"] = t.taping_line_from_flange_back_m;
    d["nominal_rolling_radius_m"] = t.nominal_rolling_radius_m;
    d["nominal_radius_at"] = t.nominal_radius_at == RC_RADIUS_AT_TAPING_LINE ? "taping-line" : "profile-origin";
    d["rail_cant_rad"] = t.rail_cant_rad;
    d["nominal_axle_height_m"] = height;
    return d;
  }

  py::dict options() {
    rc_wheelset_options o;
    lock_.exclusive("Wheelset", [&] { rc_wheelset_get_options(handle_, &o); });
    py::dict d;
#define RC_FIELD(name) d[#name] = o.name;
    RC_WHEELSET_DOUBLES(RC_FIELD) RC_WHEELSET_INTS(RC_FIELD)
#undef RC_FIELD
    py::list solvers;
    for (int k = 0; k < o.solver_count; ++k) solvers.append(o.solvers[k]);
    d["solvers"] = solvers;
    return d;
  }

  void set_options(const py::dict& d) {
    std::vector<std::pair<std::string, double>> values;
    std::optional<std::vector<int>> solvers;
    for (const auto& item : d) {
      const std::string key = py::str(item.first);
      if (key == "solvers") {
        try {
          solvers = item.second.cast<std::vector<int>>();
        } catch (const py::cast_error&) {
          throw py::type_error("'solvers' must be a list of rc_method numbers");
        }
        if (solvers->empty() || solvers->size() > 4) raise(RC_INVALID_INPUT, "solvers: 1 to 4 tangential solvers");
        continue;
      }
      rc_wheelset_options probe{};
      if (!assign_option(probe, key, 0.0)) raise(RC_INVALID_INPUT, "unknown wheelset option '" + key + "'");
      values.emplace_back(key, number_of(key, item.second));
    }
    lock_.exclusive("Wheelset", [&] {
      rc_wheelset_options o;
      rc_wheelset_get_options(handle_, &o);
      for (const auto& [key, value] : values) assign_option(o, key, value);
      if (solvers) {
        o.solver_count = static_cast<int>(solvers->size());
        for (std::size_t k = 0; k < solvers->size(); ++k) o.solvers[k] = (*solvers)[k];
      }
      return outcome(rc_wheelset_set_options(handle_, &o));
    }).raise_if_failed();
  }

  void reset_warm_start() {
    lock_.exclusive("Wheelset", [&] { return outcome(rc_wheelset_reset_warm_start(handle_)); }).raise_if_failed();
  }

  void time_stages(bool on) {
    lock_.exclusive("Wheelset", [&] { return outcome(rc_wheelset_time_stages(handle_, on ? 1 : 0)); })
        .raise_if_failed();
  }

  py::dict stage_times() {
    rc_wheelset_stage_times t{};
    lock_.exclusive("Wheelset", [&] { return outcome(rc_wheelset_stage_times_get(handle_, &t)); }).raise_if_failed();
    py::dict d;
    d["search_s"] = t.search_s;
    d["area_s"] = t.area_s;
    d["normal_s"] = t.normal_s;
    d["height_s"] = t.height_s;
    d["kinematics_s"] = t.kinematics_s;
    d["tangential_s"] = t.tangential_s;
    d["assembly_s"] = t.assembly_s;
    d["evaluations"] = t.evaluations;
    return d;
  }

  py::dict evaluate(const DoubleArray& row) { return evaluate_row(row, false); }
  py::dict evaluate_table(const DoubleArray& row) { return evaluate_row(row, true); }

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
    const Outcome result = lock_.exclusive("Wheelset", [&] {
      rc_status status = RC_OK;
      for (int attempt = 0; attempt < 2; ++attempt) {
        patches.assign(2 * count * per_wheel, rc_wheelset_patch{});
        status = count == 0 ? RC_OK
                            : rc_wheelset_batch_evaluate(handle_, count, cs.data(), threads, results.data(), per_wheel,
                                                         patches.data(), statuses.data());
        std::size_t needed = 0;
        for (std::size_t k = 0; k < count; ++k)
          if (statuses[k] == RC_BUFFER_TOO_SMALL)
            needed = std::max({needed, static_cast<std::size_t>(results[k].patch_count[0]),
                               static_cast<std::size_t>(results[k].patch_count[1])});
        if (needed == 0) break;
        per_wheel = needed;  // again with room for every patch
      }
      return outcome(status);
    });
    if (result.status != RC_OK) {
      bool any_state_failed = false;
      for (std::size_t k = 0; k < count; ++k) any_state_failed = any_state_failed || statuses[k] != RC_OK;
      if (!any_state_failed) result.raise_if_failed();
    }
    py::list out;
    for (std::size_t k = 0; k < count; ++k) {
      if (statuses[k] != RC_OK)
        out.append(py::none());
      else
        out.append(wheelset_result_dict(results[k], patches.data() + 2 * k * per_wheel, per_wheel));
    }
    return py::make_tuple(out, statuses, py::make_tuple(static_cast<int>(result.status), result.message));
  }

  // The wheelset table (docs/WHEELSET_TABLE.md).
  void build_table(const DoubleArray& y, const DoubleArray& yaw, const DoubleArray& loads, const py::object& progress,
                   double refine_lateral_force_fraction) {
    ProgressCallback context{progress, std::nullopt};
    const Outcome result = lock_.exclusive("Wheelset", [&] {
      const Outcome refinement = outcome(rc_wheelset_table_set_refinement(handle_, refine_lateral_force_fraction));
      if (refinement.status != RC_OK) return refinement;
      return outcome(rc_wheelset_table_build(handle_, y.data(), static_cast<std::size_t>(y.size()), yaw.data(),
                                             static_cast<std::size_t>(yaw.size()), loads.data(),
                                             static_cast<std::size_t>(loads.size()),
                                             progress.is_none() ? nullptr : &ProgressCallback::call, &context));
    });
    if (context.error) throw std::move(*context.error);
    result.raise_if_failed();
  }

  void load_table(const std::string& path) {
    lock_.exclusive("Wheelset", [&] { return outcome(rc_wheelset_table_load(handle_, path.c_str())); })
        .raise_if_failed();
  }

  void save_table(const std::string& path) {
    lock_.exclusive("Wheelset", [&] { return outcome(rc_wheelset_table_save(handle_, path.c_str())); })
        .raise_if_failed();
  }

  // The fast path of a simulation step: [Fx, Fy, Fz of the right wheel, of the left wheel (track
  // frame, N), Mz about the wheelset centre (N m)] from the table, without building result objects.
  py::array_t<double> table_forces(const DoubleArray& row) {
    if (row.ndim() != 1 || row.shape(0) != kStateColumns) raise(RC_INVALID_INPUT, "a wheelset state has 11 values");
    const rc_wheelset_state s = wheelset_state(row.data());
    rc_wheelset_result r{};
    rc_wheelset_patch patch[2][8];
    lock_.exclusive("Wheelset", [&] {
      rc_status status = rc_wheelset_evaluate_table(handle_, &s, &r);
      for (int w = 0; w < 2 && status == RC_OK; ++w) status = rc_wheelset_patches(handle_, w, 8, patch[w]);
      return outcome(status);
    }).raise_if_failed();
    py::array_t<double> out(7);
    double* f = out.mutable_data();
    double yaw_moment = 0.0;
    for (int w = 0; w < 2; ++w) {
      for (int i = 0; i < 3; ++i) f[3 * w + i] = r.wheel_force_track_N[w][i];
      const std::size_t n = std::min<std::size_t>(static_cast<std::size_t>(r.patch_count[w]), 8);
      for (std::size_t j = 0; j < n; ++j) {
        const rc_wheelset_patch& p = patch[w][j];
        const double rx = p.reference_point_track_m[0], ry = p.reference_point_track_m[1] - s.y_m;
        yaw_moment += rx * p.force_track_N[0][1] - ry * p.force_track_N[0][0];
      }
    }
    f[6] = yaw_moment;
    return out;
  }

 private:
  Outcome outcome(rc_status status) const {
    return status == RC_OK ? Outcome{} : Outcome{status, last_error(handle_, rc_wheelset_last_error)};
  }

  // One state, on the fly or from the table, with both wheels' patches read under the same lock.
  py::dict evaluate_row(const DoubleArray& row, bool from_table) {
    if (row.ndim() != 1 || row.shape(0) != kStateColumns) raise(RC_INVALID_INPUT, "a wheelset state has 11 values");
    const rc_wheelset_state s = wheelset_state(row.data(), true);
    rc_wheelset_result r{};
    std::vector<rc_wheelset_patch> patches;
    std::size_t per_wheel = 0;
    double omega = 0.0;
    lock_.exclusive("Wheelset", [&] {
      rc_status status = from_table ? rc_wheelset_evaluate_table(handle_, &s, &r) : rc_wheelset_evaluate(handle_, &s, &r);
      if (status == RC_OK) status = rc_wheelset_wheel_angular_velocity(handle_, &omega);
      if (status != RC_OK) return outcome(status);
      for (int w = 0; w < 2; ++w) per_wheel = std::max(per_wheel, static_cast<std::size_t>(r.patch_count[w]));
      patches.resize(2 * per_wheel);
      for (int w = 0; w < 2 && status == RC_OK; ++w)
        status = rc_wheelset_patches(handle_, w, per_wheel, patches.data() + static_cast<std::size_t>(w) * per_wheel);
      return outcome(status);
    }).raise_if_failed();
    py::dict d = wheelset_result_dict(r, patches.data(), per_wheel);
    d["wheel_angular_velocity_rad_per_s"] = omega;
    return d;
  }

  HandleLock lock_;
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
      .def("time_stages", &WheelsetHandle::time_stages)
      .def("stage_times", &WheelsetHandle::stage_times)
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
