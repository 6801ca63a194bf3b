// The paper's Section 4 reproduced: nH-FastSim and equivalent-ellipse FastSim against the exact
// steady-state solution on S1002/UIC60 patches (METHOD.md §9).
#include "study/paper_study.hpp"

#include <cerrno>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <fmt/format.h>
#include <fmt/ostream.h>

#include "railcontact/tangential.hpp"
#include "railcontact/error.hpp"
#include "railcontact/kalker.hpp"
#include "railcontact/wheel_rail.hpp"
#include "study/case_pool.hpp"
#include "study/mpi_cases.hpp"
#include "output/figures.hpp"
#include "output/output_directory.hpp"

namespace railcontact::study {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

constexpr double kMu = 0.3;
constexpr double kVerticalLoad = 98100.0;

// One wheel-rail patch prepared for the tangential solvers: flexibilities and normalisation.
struct PreparedPatch {
  WheelRailPatch wheel_rail;
  std::optional<NhFastSim> nh;           // flexibilities from K2 of the patch itself (coarsening 1)
  std::optional<NhFastSim> nh_default;   // as `railcontact run` computes them (automatic coarsening)
  std::optional<FastSim> paper_fastsim;  // the paper's parabola (Eq 1)
  Flexibility equivalent_ellipse;
};

NhFastSimOptions full_resolution() {
  NhFastSimOptions options;
  options.flexibility_coarsening = 1;
  return options;
}

PreparedPatch prepare(const WheelRailPair& pair, double y, int elements) {
  WheelRailPatchOptions options;
  options.vertical_load_N = kVerticalLoad;
  options.target_elements = elements;
  PreparedPatch p;
  p.wheel_rail = solve_wheel_rail_patch(pair, y, options);
  const ContactPatch& patch = p.wheel_rail.patch;
  p.nh.emplace(patch, full_resolution());
  p.nh_default.emplace(patch);
  p.paper_fastsim.emplace(patch, TractionBound::parabolic());
  // Equivalent ellipse: same area, axis ratio of the circumscribing rectangle (Piotrowski & Kik).
  const double ratio = p.wheel_rail.extent_x1_m / p.wheel_rail.extent_x2_m;
  const double a = std::sqrt(p.wheel_rail.area_m2 * ratio / M_PI), b = std::sqrt(p.wheel_rail.area_m2 / (M_PI * ratio));
  p.equivalent_ellipse = fastsim_flexibility(a, b, patch.material());
  return p;
}

// The faster of two runs of `work` (s): FFTW plans each new transform size once per process
// (0.5-2 ms), which a simulation pays once, not per contact evaluation; the second run of every
// method sees the plans of its sizes, so neither method is charged or spared them by chance.
template <typename Work>
double best_of_two_s(Work&& work) {
  double best = std::numeric_limits<double>::infinity();
  for (int run = 0; run < 2; ++run) {
    const auto start = Clock::now();
    work();
    best = std::min(best, seconds_since(start));
  }
  return best;
}

// Raw creepages from the normalised ones (Eq 22-23, f11 and f22 of the patch's own K2) and the spin
// switch (Eq 24).
Creepage creepage_of(const PreparedPatch& p, double xi_n, double eta_n, bool spin) {
  return p.nh->creepage_from_normalised(xi_n, eta_n, spin ? p.wheel_rail.spin_per_m : 0.0, kMu,
                                        p.wheel_rail.normal_force_N);
}

double magnitude(const TangentialForces& f) { return std::hypot(f.F1_N, f.F2_N); }

struct Family {
  const char* name;         // A, B, C as in the paper's Fig 5
  const char* description;
  double xi, eta;           // weights on the normalised level
  bool spin;
};
constexpr std::array<Family, 3> kFamilies{{{"A", "pure xi'", 1, 0, false},
                                           {"B", "eta' with spin from conicity", 0, 1, true},
                                           {"C", "xi' = eta' with spin from conicity", 1, 1, true}}};
constexpr std::array<double, 5> kLevels{0.1, 0.25, 0.5, 0.75, 1.0};

std::ofstream open_csv(const std::filesystem::path& path, const char* header) {
  std::ofstream f(path);
  if (!f) throw output::write_error(path, errno);
  f << header;
  return f;
}

void write_tractions(const std::filesystem::path& path, const ContactPatch& patch, const std::vector<double>& p1,
                     const std::vector<double>& p2, const std::vector<std::uint8_t>& slip) {
  std::ofstream f = open_csv(path, "x1_m,x2_m,p3_Pa,p1_Pa,p2_Pa,p_abs_Pa,slip\n");
  for (std::size_t e = 0; e < patch.elements().count(); ++e)
    fmt::print(f, "{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{}\n", patch.x1(e), patch.x2(e), patch.pressure_Pa()[e],
               p1[e], p2[e], std::hypot(p1[e], p2[e]), static_cast<int>(slip[e]));
}

struct ErrorStats {
  double max = 0, sum = 0, y_at_max = 0;
  int count = 0;
};

// Fig 5's errors, by "family/solver", and the y values skipped (several contact patches).
struct Fig5Errors {
  std::map<std::string, ErrorStats> stats;
  std::vector<double> skipped;
};

struct Timings {
  std::vector<double> exact_s, default_s, ratio_default, ratio_full, ratio_known;
};

// What the summary needs from the figures: Fig 5's errors, Fig 8's timings (by target size) and
// the study's start time.
struct SummaryInputs {
  Fig5Errors fig5;
  std::map<int, Timings> fig8;
  Clock::time_point study_start;
};

void check_options(const PaperStudyOptions& options) {
  require(options.elements >= 200 && options.elements <= 30000,
          [&] { return fmt::format("study paper: --elements must lie in [200, 30000] (got {})", options.elements); });
  require(options.y_step_m > 0 && options.y_step_m <= 4.5e-3, "study paper: --y-step-m must lie in (0, 4.5e-3] m");
  require(options.timing_samples >= 1 && options.timing_samples <= 50, "study paper: --samples must lie in [1, 50]");
}

// The errors of one y in the order they were computed ("family/solver", error): merged into the
// study's statistics in the order of y, so the means are the same sums on any number of threads.
using ErrorRecords = std::vector<std::pair<std::string, double>>;

void add_error(Fig5Errors& errors, const std::string& key, double error, double y) {
  ErrorStats& s = errors.stats[key];
  if (error > s.max) {
    s.max = error;
    s.y_at_max = y;
  }
  s.sum += error;
  ++s.count;
}

// Fig 5 at one y: every family, level and solver against `exact` (Eq 25), one fig5.csv row each.
// Returns the worst nh-fastsim error at this y.
double compare_solvers_at(const PreparedPatch& p, double y, std::ostream& fig5, ErrorRecords& errors) {
  const WheelRailPatch& wr = p.wheel_rail;
  double worst = 0;
  for (const Family& family : kFamilies) {
    for (double level : kLevels) {
      const Creepage c = creepage_of(p, family.xi * level, family.eta * level, family.spin);
      const double F_exact = magnitude(solve_rolling_exact(wr.patch, c, kMu).forces);
      const FastSim& ours = p.nh->fastsim();
      const FastSim& paper = *p.paper_fastsim;
      // railcontact's nH-FastSim with its creepage coupling; the paper's and FastSim without.
      for (const auto& [solver, fastsim, L, coupling] :
           {std::tuple{"nh-fastsim", &ours, p.nh->flexibility(), p.nh->coupling()},
            std::tuple{"nh-fastsim-default", &ours, p.nh_default->flexibility(), p.nh_default->coupling()},
            std::tuple{"nh-fastsim-paper", &paper, p.nh->flexibility(), CreepageCoupling{}},
            std::tuple{"fastsim", &paper, p.equivalent_ellipse, CreepageCoupling{}}}) {
        const double F = magnitude(fastsim->forces(c, L, kMu, coupling));
        const double error = std::fabs(F - F_exact) / F_exact;
        fmt::print(fig5, "{},{:.6f},{},{},{:.6f},{},{:.4f},{:.4f},{:.6f}\n", family.name, y, family.xi * level,
                   family.eta * level, c.phi, solver, F, F_exact, error);
        errors.emplace_back(fmt::format("{}/{}", family.name, solver), error);
        if (std::string(solver) == "nh-fastsim") worst = std::max(worst, error);
      }
    }
  }
  return worst;
}

// ---- Fig 5: relative total-force error vs y, three families, nh-fastsim and fastsim.

// Fig 5's y values: y = -4.5 mm + k --y-step-m, k = 0 ... y_count - 1 (to about 4.5 mm).
int fig5_y_count(double y_step_m) { return static_cast<int>(std::lround(9e-3 / y_step_m)) + 1; }
double fig5_y(std::size_t k, double y_step_m) { return -4.5e-3 + static_cast<double>(k) * y_step_m; }

// Fig 5 at one y, computed on its own (a thread or an MPI rank): its fig5_patches.csv row, its
// fig5.csv rows, its progress line and its errors.
struct Fig5AtY {
  std::string patch_row, fig5_rows, progress;
  ErrorRecords errors;
  bool skipped = false;  // several contact patches
};

// A y's results as text (an exact round trip), as they are sent back from a thread or rank: the
// sizes of its parts on the first line, then the parts, then one "key<TAB>error" line per error.
std::string encode_at_y(const Fig5AtY& r) {
  std::string t = fmt::format("{} {} {} {} {}\n", r.skipped ? 1 : 0, r.patch_row.size(), r.fig5_rows.size(),
                              r.progress.size(), r.errors.size());
  t += r.patch_row + r.fig5_rows + r.progress;
  for (const auto& [key, error] : r.errors) t += fmt::format("{}\t{:.17g}\n", key, error);
  return t;
}

Fig5AtY decode_at_y(const std::string& t) {
  Fig5AtY r;
  std::istringstream in(t);
  int skipped = 0;
  std::size_t a = 0, b = 0, c = 0, n = 0;
  in >> skipped >> a >> b >> c >> n;
  in.get();
  r.skipped = skipped != 0;
  std::size_t at = static_cast<std::size_t>(in.tellg());
  r.patch_row = t.substr(at, a);
  r.fig5_rows = t.substr(at + a, b);
  r.progress = t.substr(at + a + b, c);
  std::istringstream rest(t.substr(at + a + b + c));
  for (std::string line; n-- > 0 && std::getline(rest, line);) {
    const std::size_t tab = line.find('\t');
    r.errors.emplace_back(line.substr(0, tab), std::strtod(line.c_str() + tab + 1, nullptr));
  }
  return r;
}

// Fig 5 at the k-th of y_count values y: the patch and the solvers compared on it; a y with
// several contact patches is skipped (out of scope), its message in the patch row.
Fig5AtY fig5_at_y(const WheelRailPair& pair, int elements, std::size_t k, double y, int y_count) {
  Fig5AtY r;
  std::optional<PreparedPatch> p;
  try {
    p = prepare(pair, y, elements);
  } catch (const Error& e) {  // several contact patches: out of scope
    if (e.kind() != ErrorKind::several_patches) throw;
    r.patch_row = fmt::format("{:.6f},\"{}\",,,,,,,,,,,\n", y, e.what());
    r.progress = fmt::format("  y = {:+.2f} mm: skipped ({})\n", 1e3 * y, e.what());
    r.skipped = true;
    return r;
  }
  const WheelRailPatch& wr = p->wheel_rail;
  r.patch_row = fmt::format("{:.6f},ok,{:.6f},{:.6f},{:.3f},{:.6e},{},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e}\n", y,
                            wr.contact_angle_rad, wr.spin_per_m, wr.normal_force_N, wr.area_m2, wr.elements_in_contact,
                            p->nh->flexibility().L1, p->nh->flexibility().L2, p->nh->flexibility().L3,
                            p->equivalent_ellipse.L1, p->equivalent_ellipse.L2, p->equivalent_ellipse.L3);
  std::ostringstream rows;
  const double worst = compare_solvers_at(*p, y, rows, r.errors);
  r.fig5_rows = rows.str();
  r.progress = fmt::format("  [{:2}/{}] y = {:+.2f} mm: {} elements, gamma {:.4f} rad, worst nh-fastsim error {:.2f}%\n",
                           k + 1, y_count, 1e3 * y, wr.elements_in_contact, wr.contact_angle_rad, 100 * worst);
  return r;
}

// fig5.csv and fig5_patches.csv in the order of y, and the errors merged in that order.
void write_fig5_files(const std::filesystem::path& dir, const std::vector<Fig5AtY>& at, double y_step_m,
                      Fig5Errors& errors) {
  std::ofstream fig5 = open_csv(dir / "fig5.csv", "family,y,xi_n,eta_n,phi,solver,F,F_exact,rel_error\n");
  std::ofstream patches = open_csv(dir / "fig5_patches.csv",
                                   "y,status,contact_angle_rad,spin_per_m,normal_force_N,area_m2,elements,"
                                   "L1,L2,L3,L1_ellipse,L2_ellipse,L3_ellipse\n");
  for (std::size_t k = 0; k < at.size(); ++k) {
    patches << at[k].patch_row;
    fig5 << at[k].fig5_rows;
    if (at[k].skipped) errors.skipped.push_back(fig5_y(k, y_step_m));
    for (const auto& [key, error] : at[k].errors) add_error(errors, key, error, fig5_y(k, y_step_m));
  }
}

// Fig 5 over every y. Each y on its own (threads: options.threads; under mpirun over the ranks),
// its results sent back as text, kept by index and written in the order of y: the files are the
// same bytes on any number of threads or ranks. On ranks other than 0 nothing is written (and no
// errors returned).
Fig5Errors write_fig5_error_sweep(const WheelRailPair& pair, const PaperStudyOptions& options, std::ostream& progress) {
  Fig5Errors errors;
  const int y_count = fig5_y_count(options.y_step_m);
  std::vector<Fig5AtY> at(static_cast<std::size_t>(y_count));
  std::vector<std::size_t> todo(at.size());
  for (std::size_t k = 0; k < todo.size(); ++k) todo[k] = k;
  const CaseWorkerFactory factory = [&]() -> CaseWorker {
    return [&](std::size_t k) {
      return CaseResult{encode_at_y(fig5_at_y(pair, options.elements, k, fig5_y(k, options.y_step_m), y_count)), false};
    };
  };
  ProgressLine line(progress, "y values", at.size());
  std::size_t done = 0;
  run_cases_on_ranks(todo, options.threads, factory, [&](std::size_t k, CaseResult&& result) {
    at[k] = decode_at_y(result.text);
    progress << at[k].progress;
    line.done(++done);
  });
  if (MpiWorld::rank() != 0) return errors;  // another rank: its share is computed
  write_fig5_files(options.output_directory, at, options.y_step_m, errors);
  return errors;
}

// ---- Fig 6: traction maps at y = 0, nh-fastsim and exact.
void write_fig6_traction_maps(const PreparedPatch& centred, const std::filesystem::path& dir) {
  struct MapCase {
    const char* name;
    double xi_n, eta_n;
    bool spin;
  };
  const MapCase maps[] = {{"A_xi0.5", 0.5, 0, false}, {"B_eta0.5_spin", 0, 0.5, true}, {"C_xi0.5_eta0.5_spin", 0.5, 0.5, true}};
  std::ofstream fig6 = open_csv(dir / "fig6.csv", "case,solver,F1,F2,M3,adhesion_fraction\n");
  for (const MapCase& m : maps) {
    const Creepage c = creepage_of(centred, m.xi_n, m.eta_n, m.spin);
    const FastSimResult nh = centred.nh->solve(c, kMu);
    const RollingSolution exact = solve_rolling_exact(centred.wheel_rail.patch, c, kMu);
    write_tractions(dir / fmt::format("fig6_{}_nh-fastsim.csv", m.name), centred.wheel_rail.patch, nh.p1_Pa, nh.p2_Pa, nh.slip);
    write_tractions(dir / fmt::format("fig6_{}_exact.csv", m.name), centred.wheel_rail.patch, exact.p1_Pa, exact.p2_Pa,
                    exact.slip);
    fmt::print(fig6, "{},nh-fastsim,{:.4f},{:.4f},{:.6f},{:.4f}\n", m.name, nh.forces.F1_N, nh.forces.F2_N,
               nh.forces.M3_Nm, nh.adhesion_fraction);
    fmt::print(fig6, "{},exact,{:.4f},{:.4f},{:.6f},{:.4f}\n", m.name, exact.forces.F1_N, exact.forces.F2_N,
               exact.forces.M3_Nm, exact.adhesion_fraction);
  }
}

// ---- Fig 7: F1 vs xi' for y in {-3 mm, 0} and eta' in {0, 0.5 (with spin)}; `centred` is the
// patch at y = 0.
void write_fig7_creep_curves(const WheelRailPair& pair, const PreparedPatch& centred, int elements,
                             const std::filesystem::path& dir) {
  std::ofstream fig7 = open_csv(dir / "fig7.csv", "y,eta_n,xi_n,solver,F1,F2,M3\n");
  for (double y : {-3e-3, 0.0}) {
    const PreparedPatch p = y == 0.0 ? centred : prepare(pair, y, elements);
    for (double eta_n : {0.0, 0.5}) {
      for (int k = 0; k <= 12; ++k) {
        const double xi_n = 1.5 * k / 12;
        const Creepage c = creepage_of(p, xi_n, eta_n, eta_n > 0);
        const TangentialForces nh = p.nh->forces(c, kMu);
        const TangentialForces exact = solve_rolling_exact(p.wheel_rail.patch, c, kMu).forces;
        fmt::print(fig7, "{:.6f},{},{:.4f},nh-fastsim,{:.4f},{:.4f},{:.6f}\n", y, eta_n, xi_n, nh.F1_N, nh.F2_N, nh.M3_Nm);
        fmt::print(fig7, "{:.6f},{},{:.4f},exact,{:.4f},{:.4f},{:.6f}\n", y, eta_n, xi_n, exact.F1_N, exact.F2_N, exact.M3_Nm);
      }
    }
  }
}

// Fig 8: a patch of about `target` elements at a random y (the drawn y in `y`); up to 20 draws,
// as y with several contact patches are drawn again. Empty when every draw had several patches.
std::optional<PreparedPatch> random_patch(const WheelRailPair& pair, int target, std::mt19937& rng,
                                          std::uniform_real_distribution<double>& uniform, double& y) {
  std::optional<PreparedPatch> p;
  for (int attempt = 0; attempt < 20 && !p; ++attempt) {
    y = -4.5e-3 + 9e-3 * uniform(rng);
    try {
      p = prepare(pair, y, target);
    } catch (const Error& e) {  // several patches: draw again
      if (e.kind() != ErrorKind::several_patches) throw;
    }
  }
  return p;
}

// ---- Fig 8: computing time vs elements in contact, random creepages and y (seeded).
std::map<int, Timings> write_fig8_timings(const WheelRailPair& pair, const PaperStudyOptions& options,
                                          std::ostream& progress) {
  std::ofstream fig8 = open_csv(options.output_directory / "fig8.csv",
                                "target_elements,elements,y,xi_n,eta_n,coarsening,time_exact_s,"
                                "time_nh_fastsim_default_s,time_nh_fastsim_full_resolution_s,"
                                "time_nh_fastsim_flexibilities_known_s,ratio_default,ratio_full_resolution,"
                                "ratio_flexibilities_known\n");
  std::mt19937 rng(2023);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::map<int, Timings> timings;  // by target size
  double sink = 0.0;               // keeps the timed work observable
  for (int target : {500, 1000, 2000, 3000, 5000, 8000}) {
    for (int sample = 0; sample < options.timing_samples; ++sample) {
      double y = 0;
      const std::optional<PreparedPatch> p = random_patch(pair, target, rng, uniform, y);
      if (!p) continue;
      const double xi_n = uniform(rng), eta_n = uniform(rng);
      const Creepage c = creepage_of(*p, xi_n, eta_n, true);
      const ContactPatch& patch = p->wheel_rail.patch;
      // nH-FastSim as `railcontact run` computes it: FastSim's set-up, the flexibilities from K2
      // of the automatically coarsened patch, one evaluation.
      const double t_default = best_of_two_s([&] { sink += NhFastSim(patch).forces(c, kMu).F1_N; });
      const double t_full = best_of_two_s([&] { sink += NhFastSim(patch, full_resolution()).forces(c, kMu).F1_N; });
      const double t_known = best_of_two_s([&] { sink += p->nh->forces(c, kMu).F1_N; });
      const double t_exact = best_of_two_s([&] { sink += solve_rolling_exact(patch, c, kMu).forces.F1_N; });
      fmt::print(fig8, "{},{},{:.6f},{:.4f},{:.4f},{},{:.6e},{:.6e},{:.6e},{:.6e},{:.3f},{:.3f},{:.1f}\n", target,
                 p->wheel_rail.elements_in_contact, y, xi_n, eta_n, p->nh_default->coarsening(), t_exact, t_default, t_full,
                 t_known, t_exact / t_default, t_exact / t_full, t_exact / t_known);
      Timings& t = timings[target];
      t.exact_s.push_back(t_exact);
      t.default_s.push_back(t_default);
      t.ratio_default.push_back(t_exact / t_default);
      t.ratio_full.push_back(t_exact / t_full);
      t.ratio_known.push_back(t_exact / t_known);
    }
    fmt::print(progress, "  fig 8: {} elements done\n", target);
  }
  fig8.close();
  if (!std::isfinite(sink)) fmt::print(progress, "  (a timed result was not finite)\n");
  return timings;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// summary.md, Fig 5: the error table per family and solver, the maxima over all families and the
// skipped y values.
void summarise_fig5(std::ostream& md, const Fig5Errors& errors) {
  md << "## Fig 5: error vs y (levels 0.1, 0.25, 0.5, 0.75, 1.0)\n\n| family | solver | max error | at y (mm) | mean "
        "error |\n|---|---|---|---|---|\n";
  double nh_max = 0, nh_default_max = 0, nh_paper_max = 0, ellipse_max = 0;
  for (const Family& family : kFamilies)
    for (const char* solver : {"nh-fastsim", "nh-fastsim-default", "nh-fastsim-paper", "fastsim"}) {
      const auto found = errors.stats.find(fmt::format("{}/{}", family.name, solver));
      const ErrorStats s = found != errors.stats.end() ? found->second : ErrorStats{};
      fmt::print(md, "| {} ({}) | {} | {:.2f}% | {:+.1f} | {:.2f}% |\n", family.name, family.description, solver,
                 100 * s.max, 1e3 * s.y_at_max, 100 * s.sum / std::max(1, s.count));
      if (std::string(solver) == "nh-fastsim") nh_max = std::max(nh_max, s.max);
      if (std::string(solver) == "nh-fastsim-default") nh_default_max = std::max(nh_default_max, s.max);
      if (std::string(solver) == "nh-fastsim-paper") nh_paper_max = std::max(nh_paper_max, s.max);
      if (std::string(solver) == "fastsim") ellipse_max = std::max(ellipse_max, s.max);
    }
  fmt::print(md,
             "\nOver all three families: nh-fastsim max {:.2f}%, nh-fastsim with the default (coarsened) "
             "flexibilities max {:.2f}%, the paper's nh-fastsim (parabolic bound) max {:.2f}%, equivalent-ellipse "
             "fastsim max {:.2f}%.\n",
             100 * nh_max, 100 * nh_default_max, 100 * nh_paper_max, 100 * ellipse_max);
  if (!errors.skipped.empty()) {
    md << "\nSkipped y values (several contact patches, out of scope): ";
    for (double y : errors.skipped) fmt::print(md, "{:+.2f} mm ", 1e3 * y);
    md << "(`fig5_patches.csv` has the messages).\n";
  }
}

// summary.md, Fig 8: median times and speed-ups per target size, and over all samples.
void summarise_fig8(std::ostream& md, const std::map<int, Timings>& timings) {
  md << "## Fig 8: computing time (`fig8.png`, `fig8.csv`)\n\nOne thread; each method timed as the faster of two "
        "runs (FFTW plans a new transform size once per process). nh-fastsim `default` = what `railcontact run` "
        "does: FastSim's set-up, the flexibilities from K2 of the automatically coarsened patch "
        "(NhFastSim::automatic_coarse_blocks: the factor f that leaves at least 250 coarse elements in square blocks, "
        "at least 2 from 400 elements; f along the rolling direction, f + 1 across from f = 3), one "
        "evaluation. `full resolution`: K2 of the patch itself. `known`: the evaluation alone (flexibilities from a "
        "table).\n\n| target elements | median exact | median nh-fastsim default | median exact / default | "
        "smallest exact / default | median exact / full resolution | median exact / known |\n"
        "|---|---|---|---|---|---|---|\n";
  std::vector<double> all_default, all_known;
  for (const auto& [target, t] : timings) {
    fmt::print(md, "| {} | {:.2f} ms | {:.3f} ms | {:.1f}x | {:.1f}x | {:.1f}x | {:.0f}x |\n", target,
               1e3 * median(t.exact_s), 1e3 * median(t.default_s), median(t.ratio_default),
               *std::min_element(t.ratio_default.begin(), t.ratio_default.end()), median(t.ratio_full),
               median(t.ratio_known));
    all_default.insert(all_default.end(), t.ratio_default.begin(), t.ratio_default.end());
    all_known.insert(all_known.end(), t.ratio_known.begin(), t.ratio_known.end());
  }
  fmt::print(md, "\nMedian over all samples: exact / nh-fastsim default {:.1f}x; exact / nh-fastsim evaluation alone "
                 "(flexibilities known, e.g. from a flexibility table) {:.0f}x.\n",
             median(all_default), median(all_known));
}

// ---- summary.md: the set-up, Fig 5's error table, pointers to Fig 6 and 7, Fig 8's timings.
void write_summary(const PaperStudyOptions& options, const SummaryInputs& inputs) {
  std::ofstream md(options.output_directory / "summary.md");
  md << "# The paper's Section 4: S1002 wheel on UIC60 rail (1:40)\n\n"
     << fmt::format("Fz = 98.1 kN, F3 = Fz / cos(gamma), E = 2.1e11 Pa, nu = 0.3, mu = 0.3, about {} elements in "
                    "contact per patch. Reference: `exact` (Coulomb's law, semismooth Newton; equal to the paper's "
                    "regularised reference to 1e-5). Error: |F - F_exact| / F_exact of the total tangential force "
                    "(Eq 25). Creepages normalised with f11, f22 of each patch's K2 (Eq 22-23), spin from conicity "
                    "(Eq 24). `fastsim` = FastSim with the flexibilities of the equivalent ellipse (same area, axis "
                    "ratio of the circumscribing rectangle) and the paper's parabolic bound (Eq 1); `nh-fastsim` = "
                    "railcontact's nH-FastSim (traction bound skewed towards the trailing edge, skew {:.2f}, "
                    "docs/FASTSIM.md §6); `nh-fastsim-paper` = the paper's nH-FastSim (the same flexibilities, "
                    "parabolic bound of Eq 1); `nh-fastsim-default` = railcontact's with the flexibilities `railcontact run` "
                    "computes (K2 of the automatically coarsened patch).\n\n",
                    options.elements, TractionBound{}.skew);
  summarise_fig5(md, inputs.fig5);
  md << "\n## Fig 6: traction maps at y = 0 (`fig6.png`, forces in `fig6.csv`)\n\n## Fig 7: creep curves (`fig7.png`)\n\n";
  summarise_fig8(md, inputs.fig8);
  fmt::print(md, "\nStudy run time: {:.1f} s.\n", seconds_since(inputs.study_start));
}

}  // namespace

void run_paper_study(const PaperStudyOptions& requested, std::ostream& progress) {
  check_options(requested);
  if (MpiWorld::rank() != 0) {
    // Under mpirun: the other ranks compute Fig 5's y values that rank 0 hands out, and nothing else.
    write_fig5_error_sweep(default_wheel_rail_pair(), requested, progress);
    return;
  }
  output::OutputDirectory output(requested.output_directory, &progress);  // locked, staged (docs/RELIABILITY.md "Outputs")
  PaperStudyOptions options = requested;
  options.output_directory = output.staging();
  const std::filesystem::path& dir = options.output_directory;
  SummaryInputs summary;
  summary.study_start = Clock::now();
  const WheelRailPair pair = default_wheel_rail_pair();

  summary.fig5 = write_fig5_error_sweep(pair, options, progress);

  fmt::print(progress, "Fig 6 (traction maps at y = 0) ...\n");
  const PreparedPatch centred = prepare(pair, 0.0, options.elements);  // Fig 6, and Fig 7 at y = 0
  write_fig6_traction_maps(centred, dir);

  fmt::print(progress, "Fig 7 (creep curves) ...\n");
  write_fig7_creep_curves(pair, centred, options.elements, dir);

  fmt::print(progress, "Fig 8 (computing time) ...\n");
  summary.fig8 = write_fig8_timings(pair, options, progress);

  write_summary(options, summary);
  if (options.figures) output::draw_figures("plot_paper_study.py", dir, progress);
  output.commit();
  fmt::print(progress, "Wrote {}\n", requested.output_directory.string());
}

}  // namespace railcontact::study
