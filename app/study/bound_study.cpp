// The traction-bound skew study (bound_study.hpp). For each patch: K2 and the nH-FastSim
// flexibilities once, `exact` once per creepage, then FastSim with every skew. Creepages: the
// three families of the paper's Fig 5 (pure xi'; eta' with spin; xi' = eta' with spin) at levels
// 0.1 ... 1.0, normalised with f11, f22 of the patch's K2 (Eq 22-23); spin from conicity on the
// wheel-rail patches, 0.1 1/m on the ellipses. Ellipses: c = sqrt(ab) = 6 mm, F3 = 98.1 kN.
#include "study/bound_study.hpp"
#include "study/case_pool.hpp"
#include "study/mpi_cases.hpp"
#include "output/output_directory.hpp"

#include <cerrno>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ostream.h>

#include "railcontact/tangential.hpp"
#include "railcontact/contact_patch.hpp"
#include "railcontact/error.hpp"
#include "railcontact/wheel_rail.hpp"

namespace railcontact::study {
namespace {

constexpr double kMu = 0.3;
constexpr double kLoad = 98100.0;
constexpr std::array<double, 7> kSkews{0.0, 0.3, 0.35, 0.4, 0.45, 0.5, 0.6};
constexpr std::array<double, 11> kRatios{0.1, 0.2, 0.35, 0.5, 0.7, 1.0, 1.4, 2.0, 3.0, 5.0, 10.0};

// Largest |F - F_exact| / F_exact over the 15 creepages, per skew of kSkews.
std::array<double, kSkews.size()> worst_errors(const ContactPatch& patch, double phi) {
  // nH-FastSim's flexibilities of the patch itself, then FastSim with each bound.
  NhFastSimOptions options;
  options.flexibility_coarsening = 1;
  const NhFastSim nh(patch, options);
  const Flexibility& L = nh.flexibility();
  std::vector<FastSim> fastsims;
  for (double skew : kSkews) fastsims.emplace_back(patch, TractionBound{skew});
  std::array<double, kSkews.size()> worst{};
  for (int family = 0; family < 3; ++family) {
    for (double level : {0.1, 0.25, 0.5, 0.75, 1.0}) {
      const Creepage c = nh.creepage_from_normalised(family != 1 ? level : 0.0, family != 0 ? level : 0.0,
                                                     family != 0 ? phi : 0.0, kMu, patch.normal_force_N());
      const RollingSolution exact = solve_rolling_exact(patch, c, kMu);
      const double F = std::hypot(exact.forces.F1_N, exact.forces.F2_N);
      for (std::size_t k = 0; k < kSkews.size(); ++k) {
        const TangentialForces f = fastsims[k].forces(c, L, kMu, nh.coupling());
        worst[k] = std::max(worst[k], std::fabs(std::hypot(f.F1_N, f.F2_N) / F - 1.0));
      }
    }
  }
  return worst;
}

// One patch of the study: its worst errors per skew, or skipped (several patches).
struct BoundCase {
  bool skipped = false;
  std::array<double, kSkews.size()> worst{};
  std::string progress;
};

// Sent between ranks as text, an exact round trip.
std::string encode(const BoundCase& c) {
  std::string t = fmt::format("{}\n", c.skipped ? 1 : 0);
  for (double w : c.worst) t += fmt::format("{:.17g} ", w);
  return t + "\n" + c.progress;
}
BoundCase decode(const std::string& t) {
  BoundCase c;
  std::istringstream in(t);
  int skipped = 0;
  in >> skipped;
  c.skipped = skipped != 0;
  for (double& w : c.worst) {
    std::string word;
    in >> word;
    w = std::strtod(word.c_str(), nullptr);
  }
  in.get();
  std::getline(in, c.progress, '\0');
  return c;
}

// The ellipses, then the wheel-rail positions: each case on its own (options.threads; under mpirun
// over the ranks), filed by index, so the files do not depend on the threads or ranks. An MPI rank
// other than 0 computes what it is given and returns nothing.
std::vector<BoundCase> compute_cases(const BoundStudyOptions& options, std::ostream& progress) {
  const Material steel{2.1e11, 0.3};
  const WheelRailPair pair = default_wheel_rail_pair();
  WheelRailPatchOptions patch_options;
  patch_options.vertical_load_N = kLoad;
  patch_options.target_elements = options.elements;
  const int y_count = static_cast<int>(std::lround(9e-3 / options.y_step_m)) + 1;
  std::vector<BoundCase> cases(kRatios.size() + static_cast<std::size_t>(y_count));
  const auto y_of = [&](std::size_t k) { return -4.5e-3 + static_cast<int>(k - kRatios.size()) * options.y_step_m; };
  std::vector<std::size_t> todo(cases.size());
  for (std::size_t k = 0; k < todo.size(); ++k) todo[k] = k;
  const CaseWorkerFactory factory = [&]() -> CaseWorker {
    return [&](std::size_t k) {
      BoundCase r;
      if (k < kRatios.size()) {
        const double ratio = kRatios[k];
        const double c = 6e-3, a = c * std::sqrt(ratio), b = c / std::sqrt(ratio);
        const ContactPatch patch = hertzian_patch(
            elliptical_contact_with_count(a, b, options.elements, EllipseMeshLayout::rolling_resolved), a, b, kLoad, steel);
        r.worst = worst_errors(patch, 0.1);
        r.progress = fmt::format("  ellipse a/b = {:g} done\n", ratio);
        return CaseResult{encode(r), false};
      }
      const double y = y_of(k);
      try {
        const WheelRailPatch wr = solve_wheel_rail_patch(pair, y, patch_options);
        r.worst = worst_errors(wr.patch, wr.spin_per_m);
        r.progress = fmt::format("  [{:2}/{}] y = {:+.2f} mm done\n", k - kRatios.size() + 1, y_count, 1e3 * y);
      } catch (const Error& e) {  // several patches: out of scope, as in `study paper`
        if (e.kind() != ErrorKind::several_patches) throw;
        r.skipped = true;
        r.progress = fmt::format("  y = {:+.2f} mm: skipped ({})\n", 1e3 * y, e.what());
      }
      return CaseResult{encode(r), false};
    };
  };
  ProgressLine line(progress, "patches", cases.size());
  std::size_t done = 0;
  run_cases_on_ranks(todo, options.threads, factory, [&](std::size_t k, CaseResult&& result) {
    cases[k] = decode(result.text);
    progress << cases[k].progress;
    line.done(++done);
  });
  if (MpiWorld::rank() != 0) return {};
  return cases;
}

}  // namespace

void run_bound_study(const BoundStudyOptions& options, std::ostream& progress) {
  require(options.elements >= 200 && options.elements <= 30000,
          [&] { return fmt::format("study bound: --elements must lie in [200, 30000] (got {})", options.elements); });
  require(options.y_step_m > 0 && options.y_step_m <= 4.5e-3, "study bound: --y-step-m must lie in (0, 4.5e-3] m");
  if (MpiWorld::rank() != 0) {  // under mpirun: compute the patches rank 0 hands out, nothing else
    compute_cases(options, progress);
    return;
  }
  output::OutputDirectory output(options.output_directory, &progress);  // locked, staged (docs/RELIABILITY.md "Outputs")
  const std::filesystem::path& dir = output.staging();
  std::ofstream csv(dir / "bound_sweep.csv");
  if (!csv) throw output::write_error(dir / "bound_sweep.csv", errno);
  csv << "patch,parameter,skew,worst_rel_error\n";
  std::string rows;
  std::array<double, kSkews.size()> ellipse_worst{}, wheel_rail_worst{};
  auto record = [&](const char* kind, double parameter, const std::string& label,
                    const std::array<double, kSkews.size()>& worst, std::array<double, kSkews.size()>& overall) {
    rows += "| " + label;
    for (std::size_t k = 0; k < kSkews.size(); ++k) {
      fmt::print(csv, "{},{:.6g},{},{:.6f}\n", kind, parameter, kSkews[k], worst[k]);
      rows += fmt::format(" | {:.2f} %", 100 * worst[k]);
      overall[k] = std::max(overall[k], worst[k]);
    }
    rows += " |\n";
  };

  const std::vector<BoundCase> cases = compute_cases(options, progress);
  const auto y_of = [&](std::size_t k) { return -4.5e-3 + static_cast<int>(k - kRatios.size()) * options.y_step_m; };
  for (std::size_t k = 0; k < cases.size(); ++k) {
    if (cases[k].skipped) continue;
    if (k < kRatios.size())
      record("ellipse", kRatios[k], fmt::format("ellipse a/b = {:g}", kRatios[k]), cases[k].worst, ellipse_worst);
    else
      record("wheel-rail", y_of(k), fmt::format("S1002/UIC60 y = {:+.2f} mm", 1e3 * y_of(k)), cases[k].worst,
             wheel_rail_worst);
  }

  std::ofstream md(dir / "summary.md");
  md << "# nH-FastSim's traction-bound skew (docs/FASTSIM.md)\n\n"
     << fmt::format("Largest |F - F_exact| / F_exact of nH-FastSim over the three families of the paper's Fig 5 at "
                    "levels 0.1 ... 1.0 (K2-normalised; spin from conicity on the wheel-rail patches, 0.1 1/m on the "
                    "ellipses), about {} elements per patch, mu = 0.3. Skew 0 is the paper's parabola (Eq 1); "
                    "railcontact's default is {:g}.\n\n| patch",
                    options.elements, TractionBound{}.skew);
  for (double skew : kSkews) fmt::print(md, " | skew {:g}", skew);
  md << " |\n|---";
  for (std::size_t k = 0; k < kSkews.size(); ++k) md << "|---";
  md << "|\n" << rows << "| **worst, ellipses**";
  for (double w : ellipse_worst) fmt::print(md, " | {:.2f} %", 100 * w);
  md << " |\n| **worst, wheel-rail**";
  for (double w : wheel_rail_worst) fmt::print(md, " | {:.2f} %", 100 * w);
  md << " |\n";
  md.close();
  csv.close();
  if (!md || !csv) throw Error(ErrorKind::io, "cannot write the outputs of study bound in " + dir.string());
  output.commit();
  fmt::print(progress, "Wrote {}\n", options.output_directory.string());
}

}  // namespace railcontact::study
