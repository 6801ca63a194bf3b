// Creep curves on Hertzian ellipses: nH-FastSim, FastSim (Eq 9), exact and regularised exact.
#include "study/hertz_study.hpp"

#include <cerrno>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ostream.h>

#include "railcontact/tangential.hpp"
#include "railcontact/contact_patch.hpp"
#include "railcontact/error.hpp"
#include "railcontact/kalker.hpp"
#include "output/figures.hpp"
#include "output/output_directory.hpp"

namespace railcontact::study {
namespace {

using Clock = std::chrono::steady_clock;

struct Family {
  const char* name;
  // Creepage for normalised magnitude s (xi' = xi f11 / (3 mu F3) etc., Kalker's normalisation).
  double xi, eta, spin;  // weights on xi', eta', phi'
};

constexpr std::array<Family, 4> kFamilies{{{"xi", 1, 0, 0}, {"eta", 0, 1, 0}, {"phi", 0, 0, 1},
                                           {"combined", 0.6, 0.6, 0.5}}};
constexpr std::array<double, 3> kRatios{0.5, 1.0, 2.0};

struct Accumulated {
  double max_error = 0.0;     // max |F - F_exact| / F_exact (total tangential force, paper Eq 25)
  double max_absolute = 0.0;  // max |F - F_exact| / (mu F3)
  double max_moment = 0.0;    // max |M3 - M3_exact| / (mu F3 c), c = sqrt(ab)
};

const Material kMaterial{2.1e11, 0.3};
constexpr double kLoad = 98100.0, kMu = 0.3, kC = 5e-3;
constexpr std::array<const char*, 4> kSolvers{"nh-fastsim", "fastsim", "exact", "exact-regularised"};

// What the summary needs, gathered over all ellipses and creepages.
struct Tallies {
  std::map<std::string, Accumulated> stats;  // key: family/solver
  std::map<std::string, double> time_sum;    // key: solver
  std::map<std::string, int> time_count;
};

// One ellipse a/b = ratio with c = sqrt(ab) = kC: its Hertzian patch (rolling-resolved mesh)
// and Kalker's normalisation with the linear theory of this ellipse.
struct Ellipse {
  double ratio = 0, a = 0, b = 0, c = 0;
  ContactPatch patch;
  double F3 = 0;
  double f11 = 0, f22 = 0, f23 = 0;
  double moment_scale = 0;  // mu F3 c
};

Ellipse ellipse_of(double ratio, int elements) {
  Ellipse e;
  e.ratio = ratio;
  e.a = kC * std::sqrt(ratio);
  e.b = kC / std::sqrt(ratio);
  e.patch = hertzian_patch(elliptical_contact_with_count(e.a, e.b, elements, EllipseMeshLayout::rolling_resolved), e.a,
                           e.b, kLoad, kMaterial);
  e.F3 = e.patch.normal_force_N();
  const KalkerCoefficients C = kalker_coefficients(ratio, kMaterial.poisson_ratio);
  const double G = kMaterial.shear_modulus_Pa();
  e.c = std::sqrt(e.a * e.b);
  e.f11 = G * e.c * e.c * C.C11;
  e.f22 = G * e.c * e.c * C.C22;
  e.f23 = G * e.c * e.c * e.c * C.C23;
  e.moment_scale = kMu * e.F3 * e.c;
  return e;
}

// The raw creepage of a family at normalised magnitude s: xi = xi' 3 mu F3 / f11 etc.
Creepage creepage_at(const Ellipse& e, const Family& family, double s) {
  return Creepage{family.xi * s * 3 * kMu * e.F3 / e.f11, family.eta * s * 3 * kMu * e.F3 / e.f22,
                  family.spin * s * 3 * kMu * e.F3 / e.f23};
}

// The four solvers (kSolvers' order) at one creepage point.
struct PointResult {
  std::array<TangentialForces, 4> forces;
  std::array<double, 4> adhesion{}, seconds{};
};

// Each solver timed; nh-fastsim's time includes its flexibilities (computed once per ellipse,
// counted in every point).
PointResult solve_point(const ContactPatch& patch, const NhFastSim& nh, double nh_flexibility_time,
                        const FastSim& classical, const Flexibility& original, const Creepage& creepage) {
  PointResult result;
  for (int i = 0; i < 4; ++i) {
    const auto t = Clock::now();
    if (i < 2) {
      const FastSimResult r = i == 0 ? nh.solve(creepage, kMu) : classical.solve(creepage, original, kMu);
      result.forces[i] = r.forces;
      result.adhesion[i] = r.adhesion_fraction;
    } else {
      const RollingSolution r =
          i == 2 ? solve_rolling_exact(patch, creepage, kMu) : solve_rolling_regularised(patch, creepage, kMu);
      result.forces[i] = r.forces;
      result.adhesion[i] = r.adhesion_fraction;
    }
    result.seconds[i] = std::chrono::duration<double>(Clock::now() - t).count() + (i == 0 ? nh_flexibility_time : 0.0);
  }
  return result;
}

// One creep_curves.csv row per solver, and the differences to `exact` into the tallies.
void record_point(std::ostream& csv, const Ellipse& e, const Family& family, double s, const Creepage& creepage,
                  const PointResult& r, Tallies& tallies) {
  const double F_exact = std::hypot(r.forces[2].F1_N, r.forces[2].F2_N);
  for (int i = 0; i < 4; ++i) {
    tallies.time_sum[kSolvers[i]] += r.seconds[i];
    tallies.time_count[kSolvers[i]] += 1;
  }
  for (int i = 0; i < 4; ++i) {
    const double F = std::hypot(r.forces[i].F1_N, r.forces[i].F2_N);
    fmt::print(csv, "{},{},{:.4f},{:.6e},{:.6e},{:.6e},{},{:.6f},{:.6f},{:.8f},{:.6f},{:.4f},{:.6f}\n", e.ratio,
               family.name, s, creepage.xi, creepage.eta, creepage.phi, kSolvers[i], r.forces[i].F1_N,
               r.forces[i].F2_N, r.forces[i].M3_Nm, F / (kMu * e.F3), r.adhesion[i], r.seconds[i]);
    Accumulated& acc = tallies.stats[fmt::format("{}/{}", family.name, kSolvers[i])];
    acc.max_error = std::max(acc.max_error, std::fabs(F - F_exact) / F_exact);
    acc.max_absolute = std::max(acc.max_absolute, std::fabs(F - F_exact) / (kMu * e.F3));
    acc.max_moment = std::max(acc.max_moment, std::fabs(r.forces[i].M3_Nm - r.forces[2].M3_Nm) / e.moment_scale);
  }
}

// Progress through all points of the study.
struct Counter {
  int done = 0;
  int total = 0;
};

// One ellipse: its patch, the solvers set up once, every family's creep curve.
void run_ellipse(double ratio, const HertzStudyOptions& options, std::ostream& csv, Tallies& tallies, Counter& counter,
                 std::ostream& progress) {
  const Ellipse e = ellipse_of(ratio, options.elements);
  const ContactPatch& patch = e.patch;
  const FastSim classical(patch, TractionBound::parabolic());  // classical FastSim: Eq 1
  const auto t0 = Clock::now();
  NhFastSimOptions nh_options;  // railcontact's bound; K2 of the patch itself
  nh_options.flexibility_coarsening = 1;
  const NhFastSim nh(patch, nh_options);
  const double nh_flexibility_time = std::chrono::duration<double>(Clock::now() - t0).count();
  const Flexibility original = fastsim_flexibility(e.a, e.b, kMaterial);
  for (const Family& family : kFamilies) {
    for (int k = 1; k <= options.points; ++k) {
      const double s = 1.5 * k / options.points;  // up to 1.5: full slip beyond ~1
      const Creepage creepage = creepage_at(e, family, s);
      const PointResult r = solve_point(patch, nh, nh_flexibility_time, classical, original, creepage);
      record_point(csv, e, family, s, creepage, r, tallies);
      const double F_exact = std::hypot(r.forces[2].F1_N, r.forces[2].F2_N);
      ++counter.done;
      fmt::print(progress, "  [{:3}/{}] a/b = {} {:<8} s = {:.2f}: |F|/muF3 exact {:.3f}, nh-fastsim {:+.2f}%\n",
                 counter.done, counter.total, ratio, family.name, s, F_exact / (kMu * e.F3),
                 100 * (std::hypot(r.forces[0].F1_N, r.forces[0].F2_N) - F_exact) / F_exact);
    }
  }
}

void write_summary(const HertzStudyOptions& options, Tallies& tallies, Clock::time_point start) {
  std::ofstream md(options.output_directory / "summary.md");
  md << "# Creep curves on Hertzian ellipses\n\n"
     << fmt::format("a/b = 0.5, 1, 2 (c = 5 mm), F3 = 98.1 kN, E = 2.1e11 Pa, nu = 0.3, mu = 0.3, about {} elements "
                    "in contact (rolling-resolved mesh). Creepages normalised with Kalker's linear theory: "
                    "xi' = xi f11/(3 mu F3), eta' = eta f22/(3 mu F3), phi' = phi f23/(3 mu F3), from 0 to 1.5 in {} "
                    "steps; combined: xi' = eta' = 0.6 s, phi' = 0.5 s.\n\n",
                    options.elements, options.points)
     << "Largest differences to `exact` over the three ellipses and all creepages of a family: |F| relative "
        "(|F - F_exact|/F_exact, the paper's Eq 25), |F| relative to the saturation (|F - F_exact|/(mu F3)), and "
        "M3 relative to mu F3 c (c = sqrt(ab)).\n\n"
     << "| family | solver | max rel. error of |F| | max error / (mu F3) | max error of M3 / (mu F3 c) |\n|---|---|---|---|---|\n";
  for (const Family& family : kFamilies)
    for (const char* solver : kSolvers) {
      if (std::string(solver) == "exact") continue;
      const Accumulated& acc = tallies.stats[fmt::format("{}/{}", family.name, solver)];
      fmt::print(md, "| {} | {} | {:.2f}% | {:.2f}% | {:.2f}% |\n", family.name, solver, 100 * acc.max_error,
                 100 * acc.max_absolute, 100 * acc.max_moment);
    }
  md << "\nMean time per creepage point (nh-fastsim includes its flexibilities, computed once per ellipse and "
        "counted in every point):\n\n| solver | mean time (ms) |\n|---|---|\n";
  for (const char* solver : kSolvers)
    fmt::print(md, "| {} | {:.2f} |\n", solver, 1e3 * tallies.time_sum[solver] / std::max(1, tallies.time_count[solver]));
  fmt::print(md, "\nStudy run time: {:.1f} s. Figure: `creep_curves.png`.\n",
             std::chrono::duration<double>(Clock::now() - start).count());
}

}  // namespace

void run_hertz_study(const HertzStudyOptions& requested, std::ostream& progress) {
  require(requested.elements >= 100 && requested.elements <= 50000, [&] {
    return fmt::format("study hertz: --elements must lie in [100, 50000] (got {})", requested.elements);
  });
  require(requested.points >= 2 && requested.points <= 100, "study hertz: --points must lie in [2, 100]");
  output::OutputDirectory output(requested.output_directory, &progress);  // locked, staged (docs/RELIABILITY.md "Outputs")
  HertzStudyOptions options = requested;
  options.output_directory = output.staging();
  const std::filesystem::path& dir = options.output_directory;
  std::ofstream csv(dir / "creep_curves.csv");
  if (!csv) throw output::write_error(dir / "creep_curves.csv", errno);
  csv << "a_over_b,family,creepage_normalised,xi,eta,phi,solver,F1,F2,M3,F_over_muF3,adhesion_fraction,time_s\n";
  Tallies tallies;
  const auto start = Clock::now();
  Counter counter{0, static_cast<int>(kRatios.size() * kFamilies.size()) * options.points};
  for (double ratio : kRatios) run_ellipse(ratio, options, csv, tallies, counter, progress);
  csv.close();
  write_summary(options, tallies, start);
  if (options.figures) output::draw_figures("plot_hertz_study.py", dir, progress);
  output.commit();
  fmt::print(progress, "Wrote {}\n", requested.output_directory.string());
}

}  // namespace railcontact::study
