// The wheel–rail patch study (docs/WHEEL_RAIL.md §6): the normal contact of S1002 on UIC60 1:40
// for y = −4.5 … 4.5 mm, with the Hertz solution of the local curvatures for comparison.
#include "study/patch_study.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <cerrno>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "railcontact/error.hpp"
#include "railcontact/wheel_rail.hpp"
#include "study/case_pool.hpp"
#include "output/figures.hpp"
#include "output/output_directory.hpp"
#include "study/patch_files.hpp"

namespace railcontact::study {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

struct Row {
  double y_m = 0.0;
  std::string status;   // single, several_patches, error
  std::string message;  // for several_patches and error
  std::string patch_file;
  bool solved = false;  // the fields below are those of the (largest) patch
  WheelRailPatch patch;
  double solve_time_s = 0.0;
  double hertz_area_m2 = kNan;
  double hertz_max_pressure_Pa = kNan;
  double hertz_approach_m = kNan;
  // Centre of pressure on the profiles: the tangent-plane point C + x2 X2, X2 = (−cos γ, sin γ)
  // in the profile frame (docs/GEOMETRY.md §3).
  double centre_y_rail_m = kNan;
  double centre_y_wheel_m = kNan;
  // area / (π/4 L1 L2): 1 for an ellipse (up to the staircase), 1 for a rectangle would be 4/π.
  double ellipse_fill = kNan;
};

std::vector<double> displacements(const PatchStudyOptions& o) {
  require(std::isfinite(o.y_from_m) && std::isfinite(o.y_to_m) && o.y_to_m >= o.y_from_m,
          "study patches: the y range must be finite with --y-to-m >= --y-from-m");
  require(std::isfinite(o.y_step_m) && o.y_step_m > 0.0, "study patches: --y-step-m must be positive");
  const double count = std::floor((o.y_to_m - o.y_from_m) / o.y_step_m + 1e-9) + 1.0;
  require(count <= 1000, "study patches: at most 1000 values of y");
  std::vector<double> y;
  for (int k = 0; k < static_cast<int>(count); ++k) {
    const double value = o.y_from_m + k * o.y_step_m;
    y.push_back(std::abs(value) < 1e-12 ? 0.0 : value);  // no -0.0 in file names
  }
  return y;
}

std::string patch_file_name(double y_m) { return fmt::format("patch_y{:+.2f}mm.csv", y_m * 1e3); }

Row solve_row(const WheelRailPair& pair, double y_m, const PatchStudyOptions& options,
              const std::filesystem::path& dir) {
  WheelRailPatchOptions patch_options;
  patch_options.vertical_load_N = options.vertical_load_N;
  patch_options.target_elements = options.elements;
  patch_options.allow_several_patches = true;  // reported in the status column, not thrown
  Row row;
  row.y_m = y_m;
  const auto start = std::chrono::steady_clock::now();
  try {
    row.patch = solve_wheel_rail_patch(pair, y_m, patch_options);
  } catch (const Error& e) {
    row.status = "error";
    row.message = e.what();
    return row;
  }
  row.solve_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  row.solved = true;
  const WheelRailPatch& p = row.patch;
  if (p.patches == 1) {
    row.status = "single";
  } else {
    row.status = "several_patches";
    row.message = fmt::format("{} patches carrying", p.patches);
    for (std::size_t k = 0; k < p.patches; ++k)
      row.message += fmt::format("{} {:.1f} % (x2 = {:+.1f} mm)", k == 0 ? "" : ",", 100 * p.regions[k].load_fraction,
                                 p.regions[k].x2_centre_m * 1e3);
    row.message += "; the columns describe the largest one";
  }
  if (p.local_hertz.a_m > 0.0) {
    row.hertz_area_m2 = M_PI * p.local_hertz.a_m * p.local_hertz.b_m;
    row.hertz_max_pressure_Pa = p.local_hertz.max_pressure_Pa;
    row.hertz_approach_m = p.local_hertz.approach_m;
  }
  const double cos_gamma = std::cos(p.contact_angle_rad);
  row.centre_y_rail_m = p.pressure_centre_y_rail_m;
  row.centre_y_wheel_m = p.contact.y_wheel_m - p.pressure_centre_x2_m * cos_gamma;
  row.ellipse_fill = p.area_m2 / (M_PI / 4 * p.extent_x1_m * p.extent_x2_m);
  row.patch_file = patch_file_name(y_m);
  write_pressure_csv(dir / row.patch_file, p.patch);
  return row;
}

void write_csv(const std::filesystem::path& path, const std::vector<Row>& rows) {
  std::ofstream csv(path);
  if (!csv) throw output::write_error(path, errno);
  csv << "y_m,status,patches,contact_angle_rad,rolling_radius_m,spin_per_m,normal_force_N,area_m2,"
         "elements_in_contact,extent_x1_m,extent_x2_m,max_pressure_Pa,approach_m,iterations,"
         "y_rail_m,y_wheel_m,y_track_m,pressure_centre_x2_m,centre_y_rail_m,centre_y_wheel_m,centre_contact_angle_rad,"
         "A_per_m,B_per_m,"
         "hertz_area_m2,hertz_max_pressure_Pa,hertz_approach_m,ellipse_fill,dx1_m,dx2_m,n1,n2,mesh_passes,"
         "solve_time_s,patch_file\n";
  for (const Row& r : rows) {
    if (!r.solved) {
      fmt::print(csv, "{:.6g},{},0{}\n", r.y_m, r.status, std::string(31, ','));
      continue;
    }
    const WheelRailPatch& p = r.patch;
    const WheelRailContactPoint& c = p.contact;
    const Mesh& m = p.potential_area;
    fmt::print(csv, "{:.6g},{},{},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{},{:.9g},{:.9g},{:.9g},{:.9g},{},", r.y_m,
               r.status, p.patches, p.contact_angle_rad, p.rolling_radius_m, p.spin_per_m, p.normal_force_N, p.area_m2,
               p.elements_in_contact, p.extent_x1_m, p.extent_x2_m, p.max_pressure_Pa, p.approach_m, p.iterations);
    fmt::print(csv, "{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.6f},",
               c.y_rail_m, c.y_wheel_m, c.y_track_m, p.pressure_centre_x2_m, r.centre_y_rail_m, r.centre_y_wheel_m,
               p.pressure_centre_contact_angle_rad, c.A_per_m, c.B_per_m, r.hertz_area_m2, r.hertz_max_pressure_Pa,
               r.hertz_approach_m, r.ellipse_fill);
    fmt::print(csv, "{:.9g},{:.9g},{},{},{},{:.6f},{}\n", m.dx1_m, m.dx2_m, m.n1, m.n2, p.mesh_passes, r.solve_time_s,
               r.patch_file);
  }
  if (!csv) throw output::write_error(path, errno);
}

std::string ratio_text(double value, double reference) {
  return std::isfinite(reference) ? fmt::format("{:.3f}", value / reference) : std::string("–");
}

void write_summary(const std::filesystem::path& path, const PatchStudyOptions& o, const std::vector<Row>& rows,
                   const std::string& wheel, const std::string& rail, double total_s) {
  std::ofstream md(path);
  if (!md) throw output::write_error(path, errno);
  md << "# Wheel–rail normal contact over the wheelset displacement (METHOD.md §9)\n\n";
  fmt::print(md, "Wheel `{}` on rail `{}`; vertical load Fz = {} N, F3 = Fz / cos γ; E = 2.1e11 Pa, ν = 0.3; "
                 "about {} elements in contact (rolling-resolved mesh); y from {} to {} mm in steps of {} mm. "
                 "Spin φ = +2 sin γ / d (Eq 24, right wheel, d = 0.92 m).\n\n",
             wheel, rail, o.vertical_load_N, o.elements, o.y_from_m * 1e3, o.y_to_m * 1e3, o.y_step_m * 1e3);
  md << "Hertz: the ellipse of the contact point's local curvatures A, B and the same F3. Shape measure "
        "\"fill\" = area / (π/4 · L1 · L2), L1, L2 the patch extents: 1 for an ellipse.\n\n";
  md << "| y (mm) | status | γ (rad) | y_rail (mm) | φ (1/m) | F3 (kN) | area (mm²) | area / Hertz | elements | "
        "L1 × L2 (mm) | fill | p max (MPa) | p max / Hertz p0 | δ (µm) | iter. |\n";
  md << "|---:|---|---:|---:|---:|---:|---:|---:|---:|---|---:|---:|---:|---:|---:|\n";
  int single = 0;
  double worst_area = 1.0, worst_area_y = 0.0, worst_pressure = 1.0, worst_pressure_y = 0.0;
  double fill_min = 10.0, fill_max = 0.0;
  for (const Row& r : rows) {
    if (!r.solved) {
      fmt::print(md, "| {:+.2f} | {} | | | | | | | | | | | | | |\n", r.y_m * 1e3, r.status);
      continue;
    }
    const WheelRailPatch& p = r.patch;
    if (r.status == "single") ++single;
    fmt::print(md, "| {:+.2f} | {} | {:.5f} | {:.2f} | {:+.4f} | {:.2f} | {:.1f} | {} | {} | {:.2f} × {:.2f} | "
                   "{:.3f} | {:.0f} | {} | {:.2f} | {} |\n",
               r.y_m * 1e3, r.status, p.contact_angle_rad, p.contact.y_rail_m * 1e3, p.spin_per_m,
               p.normal_force_N * 1e-3, p.area_m2 * 1e6, ratio_text(p.area_m2, r.hertz_area_m2), p.elements_in_contact,
               p.extent_x1_m * 1e3, p.extent_x2_m * 1e3, r.ellipse_fill, p.max_pressure_Pa * 1e-6,
               ratio_text(p.max_pressure_Pa, r.hertz_max_pressure_Pa), p.approach_m * 1e6, p.iterations);
    if (r.status != "single") continue;  // the statistics below cover the single patches
    if (std::isfinite(r.hertz_area_m2) && std::abs(p.area_m2 / r.hertz_area_m2 - 1) > std::abs(worst_area - 1)) {
      worst_area = p.area_m2 / r.hertz_area_m2;
      worst_area_y = r.y_m;
    }
    if (std::isfinite(r.hertz_max_pressure_Pa) &&
        std::abs(p.max_pressure_Pa / r.hertz_max_pressure_Pa - 1) > std::abs(worst_pressure - 1)) {
      worst_pressure = p.max_pressure_Pa / r.hertz_max_pressure_Pa;
      worst_pressure_y = r.y_m;
    }
    fill_min = std::min(fill_min, r.ellipse_fill);
    fill_max = std::max(fill_max, r.ellipse_fill);
  }
  fmt::print(md, "\n**{} of {} positions give a single patch.**", single, rows.size());
  bool any_other = false;
  for (const Row& r : rows) {
    if (r.status == "single") continue;
    if (!any_other) md << " The others:\n\n";
    any_other = true;
    fmt::print(md, "- y = {:+.2f} mm: {}: {}\n", r.y_m * 1e3, r.status, r.message);
  }
  md << (any_other ? "\n" : "\n\n");
  if (single > 0) {
    fmt::print(md, "Single patches, largest deviation from Hertz: area × {:.3f} at y = {:+.2f} mm, maximum pressure × "
                   "{:.3f} at y = {:+.2f} mm; fill between {:.3f} and {:.3f}.\n\n",
               worst_area, worst_area_y * 1e3, worst_pressure, worst_pressure_y * 1e3, fill_min, fill_max);
  }
  for (std::size_t k = 0; k + 1 < rows.size(); ++k) {
    if (!rows[k].solved || !rows[k + 1].solved) continue;
    const double jump = rows[k + 1].patch.contact.y_rail_m - rows[k].patch.contact.y_rail_m;
    if (std::abs(jump) > 3e-3)
      fmt::print(md, "The point of first touch jumps by {:+.1f} mm on the rail between y = {:+.2f} and {:+.2f} mm "
                     "(centre of pressure: {:+.1f} mm).\n\n",
                 jump * 1e3, rows[k].y_m * 1e3, rows[k + 1].y_m * 1e3,
                 (rows[k + 1].centre_y_rail_m - rows[k].centre_y_rail_m) * 1e3);
  }
  md << "Files: `patches.csv` (all numbers, SI units; status single / several_patches / error), "
        "`patch_y<y>mm.csv` (x1_m, x2_m, pressure_Pa per contact element, contact frame, origin at the centre of "
        "pressure), `contact_position.png` (contact position on rail and wheel and γ against y), "
        "`patch_size.png` (area and maximum pressure against Hertz), `patch_shapes.png` (the pressure maps).\n";
  fmt::print(md, "\nStudy run time: {:.1f} s.\n", total_s);
}

}  // namespace

int run_patch_study(const PatchStudyOptions& options, std::ostream& progress) {
  require(std::isfinite(options.vertical_load_N) && options.vertical_load_N > 0.0,
          [&] { return fmt::format("study patches: --load-N must be positive (got {} N)", options.vertical_load_N); });
  require(options.elements >= kMinimumWheelRailElements && options.elements <= kMaximumWheelRailElements, [&] {
    return fmt::format("study patches: --elements {} must lie in [{}, {}]", options.elements, kMinimumWheelRailElements,
                       kMaximumWheelRailElements);
  });
  const std::vector<double> ys = displacements(options);
  const std::filesystem::path wheel = options.wheel_profile.value_or(default_wheel_profile_path());
  const std::filesystem::path rail = options.rail_profile.value_or(default_rail_profile_path());
  const WheelRailPair pair = load_wheel_rail_pair(wheel, rail);
  output::OutputDirectory output(options.output_directory, &progress);  // locked, staged (docs/RELIABILITY.md "Outputs")
  const std::filesystem::path& dir = output.staging();
  const auto start = std::chrono::steady_clock::now();

  // Each y on its own (options.threads), its row filed by index: the files do not depend on the
  // number of threads.
  std::vector<Row> rows(ys.size());
  std::vector<std::size_t> todo(ys.size());
  for (std::size_t k = 0; k < todo.size(); ++k) todo[k] = k;
  const CaseWorkerFactory factory = [&]() -> CaseWorker {
    return [&](std::size_t k) {
      rows[k] = solve_row(pair, ys[k], options, dir);  // this y's own slot and pressure file
      return CaseResult{};
    };
  };
  ProgressLine line(progress, "y values", ys.size());
  std::size_t done = 0;
  run_cases_on_threads(todo, options.threads, factory, [&](std::size_t k, CaseResult&&) {
    const Row& r = rows[k];
    if (r.solved) {
      fmt::print(progress, "  [{:2}/{}] y = {:+.2f} mm: {}, gamma = {:.4f} rad, {} elements, area {:.1f} mm2, "
                           "p max {:.0f} MPa, {:.0f} ms\n",
                 k + 1, ys.size(), r.y_m * 1e3, r.status, r.patch.contact_angle_rad, r.patch.elements_in_contact,
                 r.patch.area_m2 * 1e6, r.patch.max_pressure_Pa * 1e-6, r.solve_time_s * 1e3);
    } else {
      fmt::print(progress, "  [{:2}/{}] y = {:+.2f} mm: {}: {}\n", k + 1, ys.size(), r.y_m * 1e3, r.status, r.message);
    }
    line.done(++done);
  });
  int single = 0;
  for (const Row& r : rows) single += r.status == "single";
  write_csv(dir / "patches.csv", rows);
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  write_summary(dir / "summary.md", options, rows, wheel.filename().string(), rail.filename().string(), total);
  if (options.figures) output::draw_figures("plot_patch_study.py", dir, progress);
  output.commit();
  fmt::print(progress, "Wrote {}\n", options.output_directory.string());
  return single;
}

}  // namespace railcontact::study
