// `railcontact study surfaces`: the planar against the conformal contact surface, and the
// automatic surface between them (see the header).
#include "study/contact_surface_study.hpp"

#include <fmt/core.h>
#include <fmt/ostream.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <fstream>
#include <limits>
#include <string>

#include "railcontact/error.hpp"
#include "railcontact/wheel_rail.hpp"
#include "output/figures.hpp"
#include "output/output_directory.hpp"
#include "study/wheel_rail_setups.hpp"

namespace railcontact::study {

namespace {

constexpr double kMm = 1e-3;
constexpr double kWheelLoad_N = WheelLoads{}.right_N;  // the sweeps' load per wheel
// The measure's bins of the summary (spread / cos γ).
constexpr std::array<double, 8> kBinEdges{0.0, 0.01, 0.02, 0.03, 0.05, 0.1, 0.2, 10.0};

// One state solved on the three surfaces.
struct ThreeSurfaces {
  WheelsetResult planar, conformal, automatic;
};

// The largest difference per track component of two forces, % of μ Fz.
using Percent3 = std::array<double, 3>;
void widen(Percent3& worst, const Vector3& a, const Vector3& b, double mu) {
  for (std::size_t i = 0; i < 3; ++i)
    worst[i] = std::max(worst[i], std::abs(a[i] - b[i]) / (mu * kWheelLoad_N) * 100.0);
}

struct Bin {
  std::size_t patches = 0;
  Percent3 planar_from_conformal{};     // conformal − planar
  Percent3 automatic_from_conformal{};  // what the automatic surface still misses
};

struct WindowSummary {
  std::string setup;
  double from_y_m = 0.0, to_y_m = 0.0;
  double weight_from = 0.0, weight_to = 0.0;
  std::array<double, 3> largest_step_percent{};  // planar, conformal, automatic: any component
  std::array<double, 3> largest_step_y_m{};
};

double right_wheel_weight(const WheelsetResult& r) {
  double w = 0.0;
  for (const WheelsetPatch& p : r.wheels[0].patches) w = std::max(w, p.conformal_weight);
  return w;
}

double measure_of(const InterpenetrationRegion& r) { return r.contact_angle_spread_rad / std::cos(r.contact_angle_rad); }

WheelsetState rolling_at(double y_m, double yaw_rad) {
  WheelsetState s;
  s.position.lateral_displacement_m = y_m;
  s.position.yaw_rad = yaw_rad;
  return s;
}

// The three wheelsets of one set-up and yaw, each warm from state to state.
struct Solvers {
  Wheelset planar, conformal, automatic;
  Solvers(const WheelsetTrack& track, const ContactSurfaceStudyOptions& o)
      : planar(track, options(o, ContactSurface::planar)),
        conformal(track, options(o, ContactSurface::conformal)),
        automatic(track, options(o, ContactSurface::automatic)) {}
  ThreeSurfaces evaluate(const WheelsetState& s) {
    return {planar.evaluate(s), conformal.evaluate(s), automatic.evaluate(s)};
  }
  static WheelsetOptions options(const ContactSurfaceStudyOptions& o, ContactSurface surface) {
    WheelsetOptions w;
    w.element_size_m = o.element_size_m;
    w.solvers = {TangentialSolver::exact};
    w.contact_surface = surface;
    w.contact_surface_switch = o.surface_switch;
    return w;
  }
};

// The fine sweep of [from, to] (the window where the right wheel's weight changed most): the
// largest step of the right wheel's force per surface.
WindowSummary sweep_window(const WheelsetTrack& track, const ContactSurfaceStudyOptions& o, const std::string& name,
                           double from_y_m, double to_y_m, double yaw_rad, std::ostream& csv) {
  WindowSummary w;
  w.setup = name;
  w.from_y_m = from_y_m;
  w.to_y_m = to_y_m;
  Solvers solvers(track, o);
  const int steps = static_cast<int>(std::lround(std::abs(to_y_m - from_y_m) / o.fine_y_step_m));
  const double direction = to_y_m < from_y_m ? -1.0 : 1.0;
  const double mu = Solvers::options(o, ContactSurface::planar).friction_coefficient;
  std::array<Vector3, 3> previous{};
  for (int k = 0; k <= steps; ++k) {
    const double y = from_y_m + direction * k * o.fine_y_step_m;
    const ThreeSurfaces r = solvers.evaluate(rolling_at(y, yaw_rad));
    const std::array<Vector3, 3> force{r.planar.wheels[0].force_track_N, r.conformal.wheels[0].force_track_N,
                                       r.automatic.wheels[0].force_track_N};
    const double weight = right_wheel_weight(r.automatic);
    if (k == 0) w.weight_from = weight;
    w.weight_to = weight;
    fmt::print(csv, "{},{:.4f},{:.4f}", name, y / kMm, weight);
    for (const Vector3& f : force) fmt::print(csv, ",{:.3f},{:.3f},{:.3f}", f[0], f[1], f[2]);
    fmt::print(csv, "\n");
    if (k > 0) {
      for (std::size_t s = 0; s < 3; ++s) {
        Percent3 step{};
        widen(step, force[s], previous[s], mu);
        const double largest = *std::max_element(step.begin(), step.end());
        if (largest > w.largest_step_percent[s]) w.largest_step_percent[s] = largest, w.largest_step_y_m[s] = y;
      }
    }
    previous = force;
  }
  return w;
}

// What summary.md gathers over all sweeps.
struct SurfaceTally {
  std::array<Bin, kBinEdges.size() - 1> bins{};
  std::vector<WindowSummary> windows;  // per set-up: its fine window at the first yaw
  std::size_t states = 0, mismatched = 0;
  std::vector<std::string> stops;  // per sweep: where and why it ended
};

// The CSV files written during the sweeps: one row per patch and state, and one per state of the
// fine windows.
struct SurfaceRows {
  std::ofstream surfaces;
  std::ofstream smoothness;
};

SurfaceRows open_surface_rows(const output::OutputDirectory& out) {
  SurfaceRows rows;
  rows.surfaces = output::open_output_file(out.path("surfaces.csv"));
  fmt::print(rows.surfaces, "setup,yaw_mrad,y_mm,side,patch,contact_angle_rad,contact_angle_spread_rad,measure,"
                            "conformal_weight,planar_Fx_N,planar_Fy_N,planar_Fz_N,conformal_Fx_N,conformal_Fy_N,"
                            "conformal_Fz_N,automatic_Fx_N,automatic_Fy_N,automatic_Fz_N\n");
  rows.smoothness = output::open_output_file(out.path("smoothness.csv"));
  fmt::print(rows.smoothness, "setup,y_mm,conformal_weight,planar_Fx_N,planar_Fy_N,planar_Fz_N,conformal_Fx_N,"
                              "conformal_Fy_N,conformal_Fz_N,automatic_Fx_N,automatic_Fy_N,automatic_Fz_N\n");
  return rows;
}

void close_surface_rows(SurfaceRows& rows, const output::OutputDirectory& out) {
  rows.surfaces.close();
  if (rows.surfaces.fail()) throw output::write_error(out.path("surfaces.csv"), errno);
  rows.smoothness.close();
  if (rows.smoothness.fail()) throw output::write_error(out.path("smoothness.csv"), errno);
}

// One state's patches on both wheels, a row each and into the bins of their measure; a wheel whose
// surfaces found different numbers of patches is left out (counted).
void record_patches(const ThreeSurfaces& r, const std::string& name, double yaw, double y, double mu,
                    std::ostream& rows, SurfaceTally& tally) {
  for (std::size_t w = 0; w < 2; ++w) {
    const std::vector<WheelsetPatch>& p = r.planar.wheels[w].patches;
    const std::vector<WheelsetPatch>& c = r.conformal.wheels[w].patches;
    const std::vector<WheelsetPatch>& a = r.automatic.wheels[w].patches;
    if (p.size() != c.size() || p.size() != a.size()) {
      ++tally.mismatched;
      continue;
    }
    for (std::size_t j = 0; j < p.size(); ++j) {
      const double measure = measure_of(a[j].region);
      fmt::print(rows, "{},{:.3f},{:.4f},{},{},{:.6f},{:.6f},{:.6f},{:.4f}", name, yaw * 1e3, y / kMm,
                 side_name(a[j].side), j, a[j].region.contact_angle_rad, a[j].region.contact_angle_spread_rad, measure,
                 a[j].conformal_weight);
      for (const WheelsetPatch* q : {&p[j], &c[j], &a[j]}) {
        const Vector3& f = q->solvers[0].force_track_N;
        fmt::print(rows, ",{:.3f},{:.3f},{:.3f}", f[0], f[1], f[2]);
      }
      fmt::print(rows, "\n");
      const std::size_t b = static_cast<std::size_t>(
          std::upper_bound(kBinEdges.begin() + 1, kBinEdges.end() - 1, measure) - (kBinEdges.begin() + 1));
      Bin& bin = tally.bins[b];
      ++bin.patches;
      widen(bin.planar_from_conformal, c[j].solvers[0].force_track_N, p[j].solvers[0].force_track_N, mu);
      widen(bin.automatic_from_conformal, c[j].solvers[0].force_track_N, a[j].solvers[0].force_track_N, mu);
    }
  }
}

// The positions of a sweep and the right wheel's conformal weight (automatic surface) at each.
struct SweepTrace {
  std::vector<double> ys, weights;
};

// The sweep at one yaw from y = 0 towards the right wheel's flange until a state cannot be
// evaluated (at y = 0 an error; else the sweep's end, said where and why in tally.stops and `log`).
SweepTrace sweep_at_yaw(const WheelsetTrack& track, const ContactSurfaceStudyOptions& o, const std::string& name,
                        double yaw, std::ostream& rows, SurfaceTally& tally, std::ostream& log) {
  Solvers solvers(track, o);
  const double mu = Solvers::options(o, ContactSurface::planar).friction_coefficient;
  SweepTrace trace;
  for (int k = 0;; ++k) {
    const double y = -k * o.y_step_m;
    ThreeSurfaces r;
    try {
      r = solvers.evaluate(rolling_at(y, yaw));
    } catch (const Error& e) {
      if (k == 0) throw Error(e.kind(), fmt::format("study surfaces: {} at y = 0, yaw {:g} rad: {}", name, yaw, e.what()));
      // The sweep's end: the flange climbs (or the contact is lost); said where and why.
      tally.stops.push_back(fmt::format("{} at yaw {:+.0f} mrad: y = {:.2f} mm: {}", name, yaw * 1e3, y / kMm, e.what()));
      fmt::print(log, "{}\n", tally.stops.back());
      break;
    }
    ++tally.states;
    trace.ys.push_back(y);
    trace.weights.push_back(right_wheel_weight(r.automatic));
    record_patches(r, name, yaw, y, mu, rows, tally);
  }
  return trace;
}

// The fine window of a sweep: the step where the right wheel's weight changes most (the first of
// equals), swept again in fine steps; none where the weight does not change.
void add_fine_window(const WheelsetTrack& track, const ContactSurfaceStudyOptions& o, const std::string& name,
                     double yaw, const SweepTrace& trace, std::ostream& smoothness, std::vector<WindowSummary>& windows) {
  const std::vector<double>& ys = trace.ys;
  const std::vector<double>& weights = trace.weights;
  std::size_t at = 0;
  for (std::size_t k = 1; k + 1 < ys.size(); ++k)
    if (std::abs(weights[k + 1] - weights[k]) > std::abs(weights[at + 1] - weights[at])) at = k;
  if (weights[at + 1] != weights[at]) windows.push_back(sweep_window(track, o, name, ys[at], ys[at + 1], yaw, smoothness));
}

void write_summary(const ContactSurfaceStudyOptions& o, const SurfaceTally& tally, std::ostream& md) {
  const std::array<Bin, kBinEdges.size() - 1>& bins = tally.bins;
  const ContactSurfaceSwitch& band = o.surface_switch;
  fmt::print(md, "# The planar and the conformal contact surface\n\n");
  fmt::print(md,
             "Each wheel–rail set-up by load (98.1 kN per wheel, μ = 0.3, 20 m/s, pure rolling) from y = 0 towards the "
             "right wheel's flange in steps of {:g} mm until the flange climbs, {:g} mm elements, the exact solver on the "
             "planar surface, the conformal surface and the automatic one (planar up to a measure of {:g}, conformal "
             "from {:g}, blended between); {} states. Per patch the measure is its contact angle spread over cos γ. "
             "Largest difference per track-frame component of a patch's force, as a share of μ Fz (Fz = {:g} kN), per "
             "range of the measure:\n\n",
             o.y_step_m / kMm, o.element_size_m / kMm, band.planar_up_to, band.conformal_from, tally.states,
             kWheelLoad_N / 1e3);
  fmt::print(md, "| measure | patches | conformal − planar Fx | Fy | Fz | automatic − conformal Fx | Fy | Fz |\n"
                 "|---|---|---|---|---|---|---|---|\n");
  for (std::size_t b = 0; b < bins.size(); ++b) {
    if (bins[b].patches == 0) continue;
    const Bin& x = bins[b];
    fmt::print(md, "| [{:g}, {:g}) | {} | {:.2f} % | {:.2f} % | {:.2f} % | {:.2f} % | {:.2f} % | {:.2f} % |\n",
               kBinEdges[b], kBinEdges[b + 1], x.patches, x.planar_from_conformal[0], x.planar_from_conformal[1],
               x.planar_from_conformal[2], x.automatic_from_conformal[0], x.automatic_from_conformal[1],
               x.automatic_from_conformal[2]);
  }
  if (tally.mismatched > 0)
    fmt::print(md, "\n{} wheel states are left out: the surfaces found different numbers of patches there (a patch "
                   "appearing at slightly different heights).\n",
               tally.mismatched);
  fmt::print(md, "\nWhere each sweep ended (the flange climbing, as a rule):\n\n");
  for (const std::string& stop : tally.stops) fmt::print(md, "- {}\n", stop);
  fmt::print(md,
             "\n## Smoothness where the automatic surface blends\n\n"
             "Per set-up at yaw {:+.0f} mrad, the step of the sweep where the right wheel's conformal weight changes most, "
             "swept again in steps of {:g} mm: the largest step of the right wheel's force (any track component, % of "
             "μ Fz) on each surface.\n\n",
             o.yaws_rad.front() * 1e3, o.fine_y_step_m / kMm);
  fmt::print(md, "| set-up | window y (mm) | weight | planar step (at y mm) | conformal step | automatic step |\n"
                 "|---|---|---|---|---|---|\n");
  for (const WindowSummary& w : tally.windows)
    fmt::print(md, "| {} | {:.2f} to {:.2f} | {:.3f} to {:.3f} | {:.3f} % ({:.3f}) | {:.3f} % ({:.3f}) | {:.3f} % ({:.3f}) |\n",
               w.setup, w.from_y_m / kMm, w.to_y_m / kMm, w.weight_from, w.weight_to, w.largest_step_percent[0],
               w.largest_step_y_m[0] / kMm, w.largest_step_percent[1], w.largest_step_y_m[1] / kMm,
               w.largest_step_percent[2], w.largest_step_y_m[2] / kMm);
}

void check_options(const ContactSurfaceStudyOptions& o) {
  validate_sweep(o.element_size_m, o.y_step_m, 2e-3, o.yaws_rad);
  require(std::isfinite(o.fine_y_step_m) && o.fine_y_step_m >= 1e-6 && o.fine_y_step_m <= o.y_step_m, [&] {
    return fmt::format("--fine-y-step-m {:g} m must lie in [1e-06, {:g}] m (the sweep's step)", o.fine_y_step_m,
                       o.y_step_m);
  });
  validate(o.surface_switch);
}

}  // namespace

void run_contact_surface_study(const ContactSurfaceStudyOptions& o, std::ostream& log) {
  check_options(o);
  const std::vector<std::filesystem::path> files = wheel_rail_setup_files(o.setups);
  require(!files.empty(), "study surfaces: no wheel-rail set-up files");

  output::OutputDirectory out(o.output_directory, &log);
  SurfaceRows rows = open_surface_rows(out);
  SurfaceTally tally;
  const auto start = std::chrono::steady_clock::now();
  const std::size_t sweeps = files.size() * o.yaws_rad.size();
  std::size_t done = 0;
  for (const std::filesystem::path& file : files) {
    const WheelsetTrack track = wheelset_track_of(read_wheel_rail_setup(file));
    const std::string name = file.stem().string();
    for (const double yaw : o.yaws_rad) {
      const SweepTrace trace = sweep_at_yaw(track, o, name, yaw, rows.surfaces, tally, log);
      // The fine window at the first yaw.
      if (yaw == o.yaws_rad.front() && trace.ys.size() > 1)
        add_fine_window(track, o, name, yaw, trace, rows.smoothness, tally.windows);
      ++done;
      const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      fmt::print(log, "{} yaw {:+.0f} mrad: {} states to y = {:.2f} mm ({}/{}), {:.0f} s left\n", name, yaw * 1e3,
                 trace.ys.size(), trace.ys.back() / kMm, done, sweeps,
                 elapsed / static_cast<double>(done) * static_cast<double>(sweeps - done));
    }
  }
  close_surface_rows(rows, out);
  std::ofstream md = output::open_output_file(out.path("summary.md"));
  write_summary(o, tally, md);
  md.close();
  if (md.fail()) throw output::write_error(out.path("summary.md"), errno);
  if (o.figures) output::draw_figures("plot_contact_surfaces.py", out.staging(), log);
  out.commit();
}

}  // namespace railcontact::study
