// Creep curves on Hertzian ellipses: nH-FastSim, FastSim (Eq 9), exact and regularised exact.
#include "study/hertz_study.hpp"

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
#include "study/figures.hpp"

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

}  // namespace

void run_hertz_study(const HertzStudyOptions& options, std::ostream& progress) {
  require(options.elements >= 100 && options.elements <= 50000,
          [&] { return fmt::format("study hertz: --elements must lie in [100, 50000] (got {})", options.elements); });
  require(options.points >= 2 && options.points <= 100, "study hertz: --points must lie in [2, 100]");
  std::filesystem::create_directories(options.output_directory);
  const auto& dir = options.output_directory;
  std::ofstream csv(dir / "creep_curves.csv");
  if (!csv) throw Error("cannot write " + (dir / "creep_curves.csv").string());
  csv << "a_over_b,family,creepage_normalised,xi,eta,phi,solver,F1,F2,M3,F_over_muF3,adhesion_fraction,time_s\n";
  const Material material{2.1e11, 0.3};
  constexpr double kLoad = 98100.0, kMu = 0.3, kC = 5e-3;
  const char* const solvers[] = {"nh-fastsim", "fastsim", "exact", "exact-regularised"};
  std::map<std::string, Accumulated> stats;  // key: family/solver
  std::map<std::string, double> time_sum;
  std::map<std::string, int> time_count;
  const auto start = Clock::now();
  int done = 0;
  const int total = static_cast<int>(kRatios.size() * kFamilies.size()) * options.points;
  for (double ratio : kRatios) {
    const double a = kC * std::sqrt(ratio), b = kC / std::sqrt(ratio);
    const ContactPatch patch = hertzian_patch(
        elliptical_contact_with_count(a, b, options.elements, EllipseMeshLayout::rolling_resolved), a, b, kLoad, material);
    const double F3 = patch.normal_force_N();
    const FastSim classical(patch, TractionBound::parabolic());       // classical FastSim: Eq 1
    const auto t0 = Clock::now();
    NhFastSimOptions nh_options;  // railcontact's bound; K2 of the patch itself
    nh_options.flexibility_coarsening = 1;
    const NhFastSim nh(patch, nh_options);
    const double nh_flexibility_time = std::chrono::duration<double>(Clock::now() - t0).count();
    const Flexibility original = fastsim_flexibility(a, b, material);
    // Kalker's normalisation with the linear theory of this ellipse.
    const KalkerCoefficients C = kalker_coefficients(ratio, material.poisson_ratio);
    const double G = material.shear_modulus_Pa(), c = std::sqrt(a * b);
    const double f11 = G * c * c * C.C11, f22 = G * c * c * C.C22, f23 = G * c * c * c * C.C23;
    const double moment_scale = kMu * F3 * c;
    for (const Family& family : kFamilies) {
      for (int k = 1; k <= options.points; ++k) {
        const double s = 1.5 * k / options.points;  // up to 1.5: full slip beyond ~1
        const Creepage creepage{family.xi * s * 3 * kMu * F3 / f11, family.eta * s * 3 * kMu * F3 / f22,
                                family.spin * s * 3 * kMu * F3 / f23};
        std::array<TangentialForces, 4> forces;
        std::array<double, 4> adhesion{}, seconds{};
        for (int i = 0; i < 4; ++i) {
          const auto t = Clock::now();
          if (i < 2) {
            const FastSimResult r = i == 0 ? nh.solve(creepage, kMu) : classical.solve(creepage, original, kMu);
            forces[i] = r.forces;
            adhesion[i] = r.adhesion_fraction;
          } else {
            const RollingSolution r =
                i == 2 ? solve_rolling_exact(patch, creepage, kMu) : solve_rolling_regularised(patch, creepage, kMu);
            forces[i] = r.forces;
            adhesion[i] = r.adhesion_fraction;
          }
          seconds[i] = std::chrono::duration<double>(Clock::now() - t).count() + (i == 0 ? nh_flexibility_time : 0.0);
          time_sum[solvers[i]] += seconds[i];
          time_count[solvers[i]] += 1;
        }
        const double F_exact = std::hypot(forces[2].F1_N, forces[2].F2_N);
        for (int i = 0; i < 4; ++i) {
          const double F = std::hypot(forces[i].F1_N, forces[i].F2_N);
          fmt::print(csv, "{},{},{:.4f},{:.6e},{:.6e},{:.6e},{},{:.6f},{:.6f},{:.8f},{:.6f},{:.4f},{:.6f}\n", ratio,
                     family.name, s, creepage.xi, creepage.eta, creepage.phi, solvers[i], forces[i].F1_N,
                     forces[i].F2_N, forces[i].M3_Nm, F / (kMu * F3), adhesion[i], seconds[i]);
          Accumulated& acc = stats[fmt::format("{}/{}", family.name, solvers[i])];
          acc.max_error = std::max(acc.max_error, std::fabs(F - F_exact) / F_exact);
          acc.max_absolute = std::max(acc.max_absolute, std::fabs(F - F_exact) / (kMu * F3));
          acc.max_moment = std::max(acc.max_moment, std::fabs(forces[i].M3_Nm - forces[2].M3_Nm) / moment_scale);
        }
        ++done;
        fmt::print(progress, "  [{:3}/{}] a/b = {} {:<8} s = {:.2f}: |F|/muF3 exact {:.3f}, nh-fastsim {:+.2f}%\n", done,
                   total, ratio, family.name, s, F_exact / (kMu * F3),
                   100 * (std::hypot(forces[0].F1_N, forces[0].F2_N) - F_exact) / F_exact);
      }
    }
  }
  csv.close();
  std::ofstream md(dir / "summary.md");
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
    for (const char* solver : solvers) {
      if (std::string(solver) == "exact") continue;
      const Accumulated& acc = stats[fmt::format("{}/{}", family.name, solver)];
      fmt::print(md, "| {} | {} | {:.2f}% | {:.2f}% | {:.2f}% |\n", family.name, solver, 100 * acc.max_error,
                 100 * acc.max_absolute, 100 * acc.max_moment);
    }
  md << "\nMean time per creepage point (nh-fastsim includes its flexibilities, computed once per ellipse and "
        "counted in every point):\n\n| solver | mean time (ms) |\n|---|---|\n";
  for (const char* solver : solvers)
    fmt::print(md, "| {} | {:.2f} |\n", solver, 1e3 * time_sum[solver] / std::max(1, time_count[solver]));
  fmt::print(md, "\nStudy run time: {:.1f} s. Figure: `creep_curves.png`.\n",
             std::chrono::duration<double>(Clock::now() - start).count());
  md.close();
  if (options.figures) draw_figures("plot_hertz_study.py", dir, progress);
  fmt::print(progress, "Wrote {}\n", dir.string());
}

}  // namespace railcontact::study
