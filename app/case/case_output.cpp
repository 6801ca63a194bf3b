#include "case/case_output.hpp"

#include <cerrno>
#include <cmath>
#include <fstream>
#include <string>

#include <fmt/format.h>
#include <fmt/ostream.h>
#include <nlohmann/json.hpp>

#include "railcontact/error.hpp"
#include "railcontact/version.h"
#include "output/figures.hpp"
#include "output/output_directory.hpp"

namespace railcontact {
namespace {

double magnitude(const TangentialForces& f) { return std::hypot(f.F1_N, f.F2_N); }

// The scale of the spin moment is mu F3 c (the largest moment the traction bound allows is of that
// order, c = sqrt(a b) of the (equivalent) ellipse). Below 1e-6 of it an exact M3 is rounding and
// discretisation noise of a moment that vanishes (e.g. pure longitudinal creepage on a symmetric
// patch: |M3| ~ 1e-12 N m against mu F3 c ~ 140 N m), and a percentage change against it is
// meaningless (it printed -88 % and -94 % for two solvers that agree with the exact one).
constexpr double kSpinMomentNoiseFloor = 1e-6;

bool significant_spin_moment(double M3_exact_Nm, const CaseResult& r) {
  const PatchSummary& s = r.summary;
  const double c_m = std::sqrt(s.a_m * s.b_m);
  const double scale_Nm = r.input.mu * s.normal_force_N * c_m;
  return std::fabs(M3_exact_Nm) > kSpinMomentNoiseFloor * scale_Nm;
}

nlohmann::json patch_json(const CaseResult& r) {
  const PatchSummary& s = r.summary;
  nlohmann::json j = {{"geometry", s.geometry},
                      {"normal_force_N", s.normal_force_N},
                      {"area_m2", s.area_m2},
                      {"max_pressure_Pa", s.max_pressure_Pa},
                      {"elements_in_contact", s.elements_in_contact},
                      {"mesh", {{"n1", s.n1}, {"n2", s.n2}, {"dx1_m", s.dx1_m}, {"dx2_m", s.dx2_m}}},
                      {"extent_x1_m", s.extent_x1_m},
                      {"extent_x2_m", s.extent_x2_m},
                      {"a_m", s.a_m},
                      {"b_m", s.b_m},
                      {"mu", r.input.mu}};
  if (s.geometry == "wheel-rail") {
    j["y_m"] = s.lateral_displacement_m;
    j["contact_angle_rad"] = s.contact_angle_rad;
    j["rolling_radius_m"] = s.rolling_radius_m;
    j["spin_per_m"] = s.spin_per_m;
    j["contact_reference"] = contact_reference_name(r.input.wheel_rail.reference);
  }
  if (r.creepage_matrix) {
    const Matrix3& K = *r.creepage_matrix;
    j["creepage_matrix_K2"] = {{K(0, 0), K(0, 1), K(0, 2)}, {K(1, 0), K(1, 1), K(1, 2)}, {K(2, 0), K(2, 1), K(2, 2)}};
  }
  return j;
}

}  // namespace

std::string case_result_json(const CaseResult& r) {
  nlohmann::json results = nlohmann::json::object();
  const SolverRun* exact = r.find(TangentialSolver::exact);
  for (const SolverRun& run : r.runs) {
    nlohmann::json j = {{"F1", run.forces.F1_N},
                        {"F2", run.forces.F2_N},
                        {"M3", run.forces.M3_Nm},
                        {"F_over_muF3", magnitude(run.forces) / (r.input.mu * r.summary.normal_force_N)},
                        {"adhesion_fraction", run.adhesion_fraction},
                        {"time_s", run.time_s},
                        {"iterations", run.iterations}};
    if (run.flexibility) {
      j["flexibility"] = {run.flexibility->L1, run.flexibility->L2, run.flexibility->L3};
      j["flexibility_time_s"] = run.flexibility_time_s;
      j["flexibility_source"] = run.flexibility_source;
    }
    if (run.kind == TangentialSolver::nh_fastsim) {
      j["traction_bound_skew"] = r.input.bound_skew;
      j["slip_direction"] = slip_direction_name(r.input.slip_direction);
    }
    if (run.kind == TangentialSolver::exact || run.kind == TangentialSolver::exact_regularised) j["krylov_iterations"] = run.krylov_iterations;
    if (exact != nullptr && magnitude(exact->forces) > 0)
      j["rel_error_F"] = std::fabs(magnitude(run.forces) - magnitude(exact->forces)) / magnitude(exact->forces);
    results[std::string(solver_name(run.kind))] = j;
  }
  nlohmann::json out = {
      {"railcontact_version", RC_VERSION_STRING},
      {"patch", patch_json(r)},
      {"creepage", {{"xi", r.creepage.xi}, {"eta", r.creepage.eta}, {"phi", r.creepage.phi}}},
      {"results", results}};
  if (const auto& v = r.flexibility_table_values) {
    out["flexibility_table"] = {{"file", r.flexibility_table_file},
                                {"target_elements", r.flexibility_table_target_elements},
                                {"y_m", v->y_m},
                                {"vertical_load_N", v->vertical_load_N},
                                {"flexibility", {v->flexibility.L1, v->flexibility.L2, v->flexibility.L3}},
                                {"f11_N", v->f11_N},
                                {"f22_N", v->f22_N},
                                {"f23_Nm", v->f23_Nm},
                                {"area_m2", v->area_m2}};
  }
  return out.dump(2);
}

void print_case_report(const CaseResult& r, std::ostream& out) {
  const PatchSummary& s = r.summary;
  fmt::print(out, "Case: {}\n", r.input.source);
  if (s.geometry == "wheel-rail")
    fmt::print(out,
               "Patch: wheel-rail, y = {:.2f} mm, contact angle {:.4f} rad, rolling radius {:.2f} mm, spin from conicity "
               "{:.4f} 1/m ({} contact reference)\n",
               1e3 * s.lateral_displacement_m, s.contact_angle_rad, 1e3 * s.rolling_radius_m, s.spin_per_m,
               contact_reference_name(r.input.wheel_rail.reference));
  fmt::print(out, "Patch: {} {:.3f} x {:.3f} mm (a, b{}), F3 = {:.1f} kN, area {:.2f} mm2, max pressure {:.0f} MPa\n",
             s.geometry, 1e3 * s.a_m, 1e3 * s.b_m, s.geometry == "ellipse" ? "" : " of the equivalent ellipse",
             1e-3 * s.normal_force_N, 1e6 * s.area_m2, 1e-6 * s.max_pressure_Pa);
  fmt::print(out, "Mesh: {} elements in contact ({} x {} mesh, {:.3f} x {:.3f} mm)\n", s.elements_in_contact, s.n1, s.n2,
             1e3 * s.dx1_m, 1e3 * s.dx2_m);
  fmt::print(out, "Creepage: xi = {:.6g}, eta = {:.6g}, phi = {:.6g} 1/m; mu = {}\n\n", r.creepage.xi, r.creepage.eta,
             r.creepage.phi, r.input.mu);
  const SolverRun* exact = r.find(TangentialSolver::exact);
  fmt::print(out, "{:<18} {:>11} {:>11} {:>10} {:>8} {:>9} {:>10}", "solver", "F1 (N)", "F2 (N)", "M3 (N m)", "|F|/muF3",
             "adhesion", "time (ms)");
  if (exact) fmt::print(out, "   {:>8} {:>8} {:>8} {:>8}", "dF1/|F|", "dF2/|F|", "dM3/M3", "d|F|/|F|");
  fmt::print(out, "\n");
  for (const SolverRun& run : r.runs) {
    fmt::print(out, "{:<18} {:>11.1f} {:>11.1f} {:>10.3f} {:>8.4f} {:>8.1f}% {:>10.2f}", solver_name(run.kind),
               run.forces.F1_N, run.forces.F2_N, run.forces.M3_Nm,
               magnitude(run.forces) / (r.input.mu * s.normal_force_N), 100 * run.adhesion_fraction, 1e3 * run.time_s);
    if (exact && run.kind != TangentialSolver::exact) {
      const double F = std::max(magnitude(exact->forces), 1e-300);
      const double M = exact->forces.M3_Nm;
      // dM3/M3 only when M3 is above the noise floor; "(M3 ≈ 0)" (8 columns wide) otherwise.
      const std::string dM3 = significant_spin_moment(M, r)
                                  ? fmt::format("{:>+7.2f}%", 100 * (run.forces.M3_Nm - M) / std::fabs(M))
                                  : std::string("(M3 ≈ 0)");
      fmt::print(out, "   {:>+7.2f}% {:>+7.2f}% {} {:>+7.2f}%", 100 * (run.forces.F1_N - exact->forces.F1_N) / F,
                 100 * (run.forces.F2_N - exact->forces.F2_N) / F, dM3, 100 * (magnitude(run.forces) - F) / F);
    }
    fmt::print(out, "\n");
  }
  for (const SolverRun& run : r.runs) {
    if (!run.flexibility) continue;
    fmt::print(out, "\n{} flexibilities: L1 = {:.4e}, L2 = {:.4e}, L3 = {:.4e} m/Pa", solver_name(run.kind),
               run.flexibility->L1, run.flexibility->L2, run.flexibility->L3);
    if (run.kind == TangentialSolver::nh_fastsim && run.flexibility_source == "table")
      fmt::print(out, " (from the flexibility table {}, interpolated at y = {:.3f} mm, Fz = {:g} N for this patch's area)",
                 r.flexibility_table_file.empty() ? "(in memory)" : r.flexibility_table_file, 1e3 * r.flexibility_table_values->y_m, r.flexibility_table_values->vertical_load_N);
    else if (run.kind == TangentialSolver::nh_fastsim)
      fmt::print(out, " (from {} in {:.1f} ms, {} GMRES iterations)", run.flexibility_source, 1e3 * run.flexibility_time_s,
                 run.iterations);
    else
      fmt::print(out, " (Eq 9, Kalker's coefficients)");
    if (run.kind == TangentialSolver::nh_fastsim && r.input.slip_direction != SlipDirection::radial)
      fmt::print(out, "; slip direction {} (docs/FASTSIM.md)", slip_direction_name(r.input.slip_direction));
  }
  fmt::print(out, "\n");
  if (const auto& v = r.flexibility_table_values) {
    fmt::print(out, "Flexibility table: f11 = {:.4e} N, f22 = {:.4e} N, f23 = {:.4e} N m (for the normalised creepages; no K2)\n",
               v->f11_N, v->f22_N, v->f23_Nm);
    const double ratio = static_cast<double>(r.summary.elements_in_contact) / r.flexibility_table_target_elements;
    if (std::fabs(ratio - 1.0) > 0.15)
      fmt::print(out, "Note: the table was built with about {} elements in contact, this patch has {}: its L are matched to "
                      "another mesh\n",
                 r.flexibility_table_target_elements, r.summary.elements_in_contact);
  }
  for (const SolverRun& run : r.runs)
    if (run.kind == TangentialSolver::exact || run.kind == TangentialSolver::exact_regularised)
      fmt::print(out, "{}: {} Newton iterations, {} GMRES iterations, converged\n", solver_name(run.kind),
                 run.iterations, run.krylov_iterations);
}

void write_case_outputs(const CaseResult& r, const std::filesystem::path& directory, std::ostream& log) {
  output::OutputDirectory output(directory, &log);
  write_case_outputs(r, output, log);
}

void write_case_outputs(const CaseResult& r, output::OutputDirectory& output, std::ostream& log) {
  const std::filesystem::path& dir = output.staging();
  auto open = [&](const std::string& name) {
    std::ofstream file(dir / name);
    if (!file) throw output::write_error(dir / name, errno);
    return file;
  };
  auto close = [&](std::ofstream& file, const std::string& name) {
    file.close();
    if (!file) throw output::write_error(dir / name, errno);
  };
  {
    std::ofstream json = open("result.json");
    json << case_result_json(r) << "\n";
    close(json, "result.json");
  }
  const ContactPatch& patch = r.patch;
  {
    std::ofstream csv = open("patch.csv");
    csv << "x1_m,x2_m,p3_Pa\n";
    for (std::size_t e = 0; e < patch.elements().count(); ++e)
      fmt::print(csv, "{:.9e},{:.9e},{:.9e}\n", patch.x1(e), patch.x2(e), patch.pressure_Pa()[e]);
    close(csv, "patch.csv");
    std::ofstream mesh = open("mesh.csv");
    fmt::print(mesh, "dx1_m,dx2_m,mu\n{:.9e},{:.9e},{}\n", patch.mesh().dx1_m, patch.mesh().dx2_m, r.input.mu);
    close(mesh, "mesh.csv");
  }
  for (const SolverRun& run : r.runs) {
    const std::string name = fmt::format("tractions_{}.csv", solver_name(run.kind));
    std::ofstream csv = open(name);
    csv << "x1_m,x2_m,p3_Pa,p1_Pa,p2_Pa,p_abs_Pa,slip\n";
    for (std::size_t e = 0; e < patch.elements().count(); ++e)
      fmt::print(csv, "{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{}\n", patch.x1(e), patch.x2(e), patch.pressure_Pa()[e],
                 run.p1_Pa[e], run.p2_Pa[e], std::hypot(run.p1_Pa[e], run.p2_Pa[e]), static_cast<int>(run.slip[e]));
    close(csv, name);
  }
  output::draw_figures("plot_tractions.py", dir, log);  // on the staged files: the figures are committed with them
  output.commit();
}

}  // namespace railcontact
