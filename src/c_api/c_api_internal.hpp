#pragma once
// The C API's internals (include/railcontact/railcontact.h, docs/C_API.md): the handles, the
// single-patch solver behind rc_solver, and the guard that turns every C++ exception into a status.
#include <cstddef>
#include <memory>
#include <new>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "railcontact/contact_patch.hpp"
#include "railcontact/error.hpp"
#include "railcontact/flexibility_table.hpp"
#include "railcontact/railcontact.h"
#include "railcontact/tangential.hpp"
#include "railcontact/tangential_model.hpp"
#include "railcontact/wheelset.hpp"
#include "railcontact/wheelset_table.hpp"

namespace railcontact::c_api {

// An error of the C layer itself with a status no ErrorKind has (buffer too small, cancelled).
struct StatusError {
  rc_status status;
  std::string message;
};

rc_status status_of(ErrorKind kind);

// Keeps the message of the last failed call of a handle. Never throws.
class LastError {
 public:
  void set(const char* message) noexcept {
    try {
      message_ = message;
    } catch (...) {
      message_.clear();  // out of memory for the message itself: an empty message
    }
  }
  [[nodiscard]] const std::string& message() const { return message_; }

 private:
  std::string message_;
};

// Runs f, returning RC_OK, or the status of the exception it throws with its message kept in
// `error`. Nothing escapes.
template <class F>
rc_status guarded(LastError* error, F&& f) noexcept {
  const auto fail = [&](rc_status status, const char* message) noexcept {
    if (error != nullptr) error->set(message);
    return status;
  };
  try {
    f();
    return RC_OK;
  } catch (const Error& e) {
    return fail(status_of(e.kind()), e.what());
  } catch (const StatusError& e) {
    return fail(e.status, e.message.c_str());
  } catch (const std::bad_alloc&) {
    return fail(RC_OUT_OF_MEMORY, "out of memory (reduce the number of elements)");
  } catch (const std::exception& e) {
    try {
      const std::string message = std::string("internal error: ") + e.what();
      return fail(RC_INTERNAL, message.c_str());
    } catch (...) {
      return fail(RC_INTERNAL, "internal error");
    }
  } catch (...) {
    return fail(RC_INTERNAL, "internal error: an unknown exception");
  }
}

// Copies a message into a caller's buffer (rc_*_last_error).
rc_status copy_message(const std::string& message, char* buffer, std::size_t size, std::size_t* length) noexcept;

// rc_*_create: a new handle in *handle (nullptr on failure).
template <class Handle>
rc_status create_handle(Handle** handle) noexcept {
  if (handle == nullptr) return RC_INVALID_INPUT;
  *handle = nullptr;
  try {
    *handle = new Handle();
    return RC_OK;
  } catch (const std::bad_alloc&) {
    return RC_OUT_OF_MEMORY;
  } catch (...) {
    return RC_INTERNAL;
  }
}

// rc_*_last_error: the handle's last message into the caller's buffer.
template <class Handle>
rc_status last_error(const Handle* handle, char* buffer, std::size_t size, std::size_t* length) noexcept {
  if (handle == nullptr) return RC_INVALID_INPUT;
  return copy_message(handle->error.message(), buffer, size, length);
}

// Checks rc_settings field by field (messages name the field, its value and its range).
void validate_settings(const rc_settings& settings);

// An rc_slip_direction value of the structure's slip_direction field; throws an invalid_input
// Error naming the field, the value and the allowed ones otherwise.
SlipDirection slip_direction_of(int value, const char* structure = "rc_settings");

// An rc_method value as the library's TangentialSolver (the same numbers); throws an invalid_input
// Error "<field> = <value> is not an rc_method (0 nh-fastsim, ...)" otherwise.
TangentialSolver method_of(int value, std::string_view field);

// A contact patch with the settings' tangential model prepared on it: immutable once built, so one
// may serve several threads (the models only read it).
struct PreparedPatch {
  ContactPatch patch;
  rc_normal_result normal{};
  double a_m = 0.0, b_m = 0.0;  // the ellipse of Eq 9 for classical FastSim (or the equivalent one)
  std::optional<NhFastSimFlexibilities> given;  // a flexibility table's, for nh-fastsim
  std::optional<TangentialModel> model;
};

// What identifies a prepared patch: the rc_patch's values (and h of a grid) under the settings
// that enter the preparation.
struct PatchKey {
  rc_patch patch{};
  std::vector<double> h_m;
  bool by_approach = false;  // a grid with the approach prescribed (patch.normal_force_N unused)
  double approach_m = 0.0;
  bool operator==(const PatchKey& other) const;
};

// One evaluation's results: forces and the tractions per contact element (patch order). FastSim's
// fields are computed only when asked for (has_fields false until then); the exact solvers give
// them with the forces.
struct Evaluation {
  rc_forces forces{};
  rc_creepage creepage{};
  bool has_fields = false;
  std::vector<double> p1_Pa, p2_Pa;
  std::vector<std::uint8_t> slip;
};

// The solver behind rc_solver (and each worker of a batch).
class SinglePatchSolver {
 public:
  SinglePatchSolver();

  [[nodiscard]] const rc_settings& settings() const { return settings_; }
  void set_settings(const rc_settings& settings);

  // Prepares the patch unless it equals the one prepared.
  void set_patch(const rc_patch& patch);
  // The same with the approach prescribed instead of the normal force (rc_solver_set_patch_at_approach).
  void set_patch_at_approach(const rc_patch& patch, double approach_m);
  void set_prepared(std::shared_ptr<const PreparedPatch> prepared, std::optional<PatchKey> key);
  [[nodiscard]] const std::shared_ptr<const PreparedPatch>& prepared() const { return prepared_; }
  [[nodiscard]] const PreparedPatch& require_patch() const;
  // The prepared patch when it is that of `patch` (else null).
  [[nodiscard]] std::shared_ptr<const PreparedPatch> prepared_for(const rc_patch& patch) const;

  // Forces (the fields of the exact solvers are kept; FastSim's are computed by last_with_fields()).
  rc_forces solve(const rc_creepage& creepage);
  // Forces and the Jacobian (row-major) by central differences.
  rc_forces jacobian(const rc_creepage& creepage, double jacobian[9]);

  [[nodiscard]] const Evaluation& last() const;
  // The last evaluation with its traction fields (computed now for FastSim: the same creepages,
  // the same numbers as one solve with the fields).
  [[nodiscard]] const Evaluation& last_with_fields() const;

  // Prepares a patch for the given settings (no state).
  // approach_m: null for the patch's normal force, else the grid's prescribed approach.
  static std::shared_ptr<const PreparedPatch> prepare(const rc_settings& settings, const rc_patch& patch,
                                                      const double* approach_m = nullptr);
  static std::shared_ptr<const PreparedPatch> prepare_wheel_rail(const rc_settings& settings,
                                                                 const FlexibilityTableFastSim& table, double y_m,
                                                                 double vertical_load_N);
  static PatchKey key_of(const rc_patch& patch);

 private:
  Evaluation evaluate(const rc_creepage& creepage, bool with_fields) const;

  rc_settings settings_{};
  std::shared_ptr<const PreparedPatch> prepared_;
  std::optional<PatchKey> key_;  // empty for a wheel-rail patch
  mutable std::optional<Evaluation> last_;  // its fields are filled in lazily (last_with_fields)
};

}  // namespace railcontact::c_api

struct rc_solver {
  railcontact::c_api::SinglePatchSolver solver;
  mutable railcontact::c_api::LastError error;  // set by const calls too
};

// The wheelset behind rc_wheelset (src/c_api/wheelset.cpp).
struct rc_wheelset {
  std::optional<railcontact::Wheelset> wheelset;  // the track and the options; empty without a track
  rc_wheelset_options options{};
  std::optional<railcontact::WheelsetResult> last;
  std::optional<railcontact::WheelsetTable> table;  // rc_wheelset_table_build / _load
  // Why the wheelset has no table: the call that dropped it and what no longer fits (empty when
  // none was dropped), for rc_wheelset_evaluate_table's message.
  std::string table_dropped;
  // rc_wheelset_table_set_refinement: WheelsetTableRefinement::lateral_force_fraction of the next
  // builds (0: none).
  double table_refinement = railcontact::kWheelsetTableRefinementDefault;  // rc_wheelset_table_set_refinement's default
  // rc_wheelset_time_stages: on, and the stage times of the evaluations since (each evaluation's
  // added from its Wheelset, which set_track, set_options and warm_start = 0 replace).
  bool time_stages = false;
  railcontact::WheelsetStageTimes stage_times;
  mutable railcontact::c_api::LastError error;  // set by const calls too
  rc_wheelset();
};

struct rc_flextable {
  std::optional<railcontact::FlexibilityTableFastSim> table;  // the table with its profile pair
  mutable railcontact::c_api::LastError error;  // set by const calls too
};
