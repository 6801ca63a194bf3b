#pragma once
// A contact case, as read from a TOML case file (`railcontact run CASE.toml`): geometry,
// material, load, friction, creepage, mesh and the solvers to run. Documented with an example
// in docs/CASE_FILES.md and examples/.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "railcontact/contact_patch.hpp"
#include "railcontact/tangential.hpp"
#include "railcontact/wheel_rail.hpp"

namespace railcontact {

enum class GeometryKind { ellipse, wheel_rail };

struct EllipseGeometry {
  // Either the semi-axes (a along X1) or the curvatures of h = A x1^2 + B x2^2 (Hertz).
  std::optional<double> a_m, b_m;
  std::optional<double> A_per_m, B_per_m;
};

struct WheelRailGeometry {
  std::string wheel_file;  // empty: the shipped S1002 wheel
  std::string rail_file;   // empty: the shipped UIC60 rail (inclined 1:40)
  double y_m = 0.0;        // wheelset lateral displacement; y < 0 towards the flange
  ContactReference reference = ContactReference::smooth;  // key contact_reference (docs/WHEEL_RAIL.md §4)
};

struct CreepageInput {
  Creepage raw;                         // xi, eta, phi as given
  std::optional<double> xi_normalised;  // xi' of Eq 22 (needs the patch's K2)
  std::optional<double> eta_normalised; // eta' of Eq 23
  bool phi_from_conicity = false;       // phi from Eq 24
};

struct Case {
  std::string source;  // file name, for messages
  GeometryKind geometry = GeometryKind::ellipse;
  EllipseGeometry ellipse;
  WheelRailGeometry wheel_rail;
  Material material;
  double normal_force_N = 0.0;
  double mu = 0.3;
  CreepageInput creepage;
  int target_elements = 2800;
  std::vector<TangentialSolver> solvers{TangentialSolver::nh_fastsim, TangentialSolver::fastsim, TangentialSolver::exact,
                                  TangentialSolver::exact_regularised};
  RollingOptions rolling;
  // nH-FastSim flexibilities (and the normalisation's f11, f22) from K2 of the patch coarsened
  // in square blocks of this factor (1: the patch itself; 2: about 4x cheaper, docs/VALIDATION.md
  // §3); 0: automatic, NhFastSim::automatic_coarse_blocks() (factor f for a coarse patch of >= 250
  // elements, 2 from 400; f x (f + 1) blocks from f = 3).
  int flexibility_coarsening = 0;
  // nh-fastsim's traction bound (tangential.hpp TractionBound): 0 = the paper's parabola (Eq 1).
  // The classical `fastsim` always uses the parabola.
  double bound_skew = TractionBound{}.skew;
  // nh-fastsim's slipping traction (docs/FASTSIM.md "The slip direction"): Eq 8 by default, as the
  // paper; flexibility-weighted for flange patches ([solvers] slip_direction, --slip-direction).
  SlipDirection slip_direction = SlipDirection::radial;
};

// Reads and validates a case file. Throws railcontact::Error naming the file, the line and the
// key for malformed TOML, unknown keys, missing sections, wrong types, non-finite or
// non-physical values and unknown solver names; Error(io) for a missing file, a directory or a
// device, Error(invalid_input) for a file over 1 MiB or one that is not UTF-8 (line and column
// of the first bad byte). Relative profile paths ([geometry] wheel, rail) are resolved against
// the case file's directory.
Case read_case_file(const std::filesystem::path& path);
// The same from the text of a case file; source_name names it in messages. Relative profile
// paths are resolved against base_directory, or left as they are (relative to the current
// directory) when it is empty.
Case parse_case(std::string_view toml_text, const std::string& source_name,
                const std::filesystem::path& base_directory = {});

}  // namespace railcontact
