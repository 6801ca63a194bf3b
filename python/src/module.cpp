// railcontact._core: the Python extension of the package railcontact (docs/PYTHON.md), a thin
// pybind11 layer over the C API (railcontact/railcontact.h). The package's Python code
// (python/railcontact/__init__.py) builds the result classes and holds the docstrings. Every solve
// releases the GIL; a failed call raises the exception class of its status (railcontact._errors).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

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
    RC_FIELD(max_newton_iterations); RC_FIELD(max_krylov_iterations); RC_FIELD(normal_max_iterations);
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
      RC_INT(max_newton_iterations) RC_INT(max_krylov_iterations) RC_INT(normal_max_iterations)
#undef RC_DOUBLE
#undef RC_INT
      raise(RC_INVALID_INPUT, "unknown setting '" + key + "'");
    }
    check(rc_solver_set_settings(handle_, &s));
  }

  void set_patch(const rc_patch& patch) {
    rc_status status;
    {
      py::gil_scoped_release release;
      status = rc_solver_set_patch(handle_, &patch);
    }
    check(status);
  }

  void set_ellipse(double a, double b, double F3) {
    rc_patch p{};
    p.kind = RC_GEOMETRY_ELLIPSE;
    p.a_m = a;
    p.b_m = b;
    p.normal_force_N = F3;
    set_patch(p);
  }
  void set_hertz(double A, double B, double F3) {
    rc_patch p{};
    p.kind = RC_GEOMETRY_HERTZ;
    p.A_per_m = A;
    p.B_per_m = B;
    p.normal_force_N = F3;
    set_patch(p);
  }
  void set_grid(const DoubleArray& h, double dx1, double dx2, double F3) {
    if (h.ndim() != 2) raise(RC_INVALID_INPUT, "h must be a 2-D array of shape (n2, n1): rows along X2, columns along X1");
    rc_patch p{};
    p.kind = RC_GEOMETRY_GRID;
    p.grid_n2 = static_cast<int>(h.shape(0));
    p.grid_n1 = static_cast<int>(h.shape(1));
    p.grid_dx1_m = dx1;
    p.grid_dx2_m = dx2;
    p.grid_h_m = h.data();
    p.normal_force_N = F3;
    set_patch(p);
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
    struct Context {
      py::object callback;
      std::optional<py::error_already_set> error;
    } context{progress, std::nullopt};
    const auto trampoline = [](std::size_t done, std::size_t total, void* user) -> int {
      auto* c = static_cast<Context*>(user);
      py::gil_scoped_acquire acquire;
      try {
        const py::object r = c->callback(done, total);
        return (!r.is_none() && r.cast<bool>() == false) ? 1 : 0;  // False stops the build
      } catch (py::error_already_set& e) {
        c->error.emplace(std::move(e));
        return 1;
      }
    };
    rc_status status;
    {
      py::gil_scoped_release release;
      status = rc_flextable_build(handle_, setup ? setup->c_str() : nullptr, y.data(), static_cast<std::size_t>(y.size()),
                                  loads.data(), static_cast<std::size_t>(loads.size()), target_elements, E, nu,
                                  progress.is_none() ? nullptr : +trampoline, &context);
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

  py::class_<FlexTable>(m, "FlexTable")
      .def(py::init<>())
      .def("load", &FlexTable::load)
      .def("save", &FlexTable::save)
      .def("build", &FlexTable::build)
      .def("info", &FlexTable::info)
      .def("lookup", &FlexTable::lookup);
}
