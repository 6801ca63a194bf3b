// `railcontact wheelset-table build`: the wheelset table of a wheelset case's profiles and track
// (docs/WHEELSET_TABLE.md). `railcontact wheelset --table FILE` evaluates states from it.
#include <fmt/core.h>
#include <fmt/ostream.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "case/wheelset_case.hpp"
#include "cli/commands.hpp"
#include "cli/option_value.hpp"
#include "case/count_text.hpp"
#include "cli/table_file_output.hpp"
#include "railcontact/error.hpp"
#include "railcontact/wheelset_table.hpp"
#include "study/case_pool.hpp"
#include "study/mpi_cases.hpp"

namespace railcontact::cli {
namespace {

struct BuildArguments {
  std::string case_file;
  std::string out;
  std::string y_m = "-0.007:0.007:0.0001";
  std::string yaw_rad = "0:0:0.001";
  // Loads in 5 kN steps: a lookup that balances the tangential forces vertically looks the wheel up
  // at another table load, interpolated linearly (docs/WHEELSET_TABLE.md §3 "The load grid").
  std::vector<double> loads_N{80e3, 85e3, 90e3, 95e3, 100e3, 105e3, 110e3, 115e3, 120e3};
  double element_size_m = 0.2e-3;
  std::string reference_weighting;  // --reference-weighting (squared-gap, depth)
  std::string contact_surface;      // --contact-surface (planar, conformal, auto)
  double refine_lateral_force = kWheelsetTableRefinementDefault;  // --refine-lateral-force-fraction (0: no refinement)
  std::string threads;
  int runtime_elements = kWheelsetTableRuntimeElements;
};

// FROM:TO:STEP (in the option's SI unit), TO reached within 1e-9 of a step; FROM = TO gives one
// value.
std::vector<double> range_values(const std::string& text, const char* option) {
  std::istringstream in(text);
  char c1 = 0, c2 = 0;
  double from = 0, to = 0, step = 0;
  in >> from >> c1 >> to >> c2 >> step;
  require(in && c1 == ':' && c2 == ':' && in.peek() == std::char_traits<char>::eof() && std::isfinite(from) &&
              std::isfinite(to) && std::isfinite(step) && step > 0.0 && to >= from,
          [&] {
            return fmt::format("{} '{}' must be FROM:TO:STEP with FROM <= TO and a positive STEP, e.g. "
                               "-0.007:0.007:0.0001",
                               option, text);
          });
  const double count = std::floor((to - from) / step + 1e-9) + 1.0;
  require(count <= 20000.0, [&] { return fmt::format("{} '{}' gives {} values; at most 20000", option, text, count_text(count)); });
  std::vector<double> values;
  for (int k = 0; k < static_cast<int>(count); ++k) values.push_back(from + k * step);
  return values;
}

// The build's threads: every core by default (one thread per rank under mpirun); the table does
// not depend on it.
int build_threads(const BuildArguments& a) {
  return a.threads.empty() ? (study::MpiWorld::several() ? 1 : study::available_cores())
                           : study::parse_threads(a.threads);
}

// The table's axes: y, yaw and the wheel loads (sorted).
WheelsetTableGrid table_grid(const BuildArguments& a) {
  WheelsetTableGrid grid;
  grid.y_m = range_values(a.y_m, "--y-m");
  grid.yaw_rad = range_values(a.yaw_rad, "--yaw-rad");
  grid.wheel_load_N.clear();
  for (double load : a.loads_N) {
    require(std::isfinite(load) && load > 0.0, [&] { return fmt::format("--load-N {:g} N must be positive", load); });
    grid.wheel_load_N.push_back(load);
  }
  std::sort(grid.wheel_load_N.begin(), grid.wheel_load_N.end());
  validate(grid);
  return grid;
}

// The nodes' wheelset: the case's, with the mesh and patch geometry given on the command line
// (the element size also by default without a case).
WheelsetOptions node_wheelset_options(const BuildArguments& a, const CLI::App& sub, const WheelsetCase& c) {
  WheelsetOptions wheelset = c.options;
  if (sub.count("--element-size-m") > 0 || a.case_file.empty()) wheelset.element_size_m = a.element_size_m;
  if (sub.count("--reference-weighting") > 0)
    wheelset.search.weighting = parse_option_value("--reference-weighting", a.reference_weighting, parse_reference_weighting);
  if (sub.count("--contact-surface") > 0)
    wheelset.contact_surface = parse_option_value("--contact-surface", a.contact_surface, parse_contact_surface);
  return wheelset;
}

// The build's options but its runner and date: the nodes' wheelset, the refinement in y and the
// size of the coarse patches a lookup runs on.
WheelsetTableOptions table_options(const BuildArguments& a, const CLI::App& sub, const WheelsetCase& c) {
  WheelsetTableOptions options;
  options.wheelset = node_wheelset_options(a, sub, c);
  require(a.refine_lateral_force >= 0.0 && a.refine_lateral_force <= 1.0, [&] {
    return fmt::format("--refine-lateral-force-fraction {:g} must lie in [0, 1] (a fraction of the wheel load; 0: no refinement)",
                       a.refine_lateral_force);
  });
  // The refinement decides from the nodes which to add: over MPI the other ranks would not know.
  // Asked for, it is refused there; by default it is left out (and the build says so).
  const bool asked = sub.count("--refine-lateral-force-fraction") > 0;
  require(a.refine_lateral_force == 0.0 || !asked || !study::MpiWorld::several(),
          "--refine-lateral-force-fraction is not available over MPI ranks: run the build on one rank (with --threads), or "
          "give the finer y steps in --y-m");
  options.refinement.lateral_force_fraction = study::MpiWorld::several() && !asked ? 0.0 : a.refine_lateral_force;
  if (study::MpiWorld::several() && !asked && study::MpiWorld::rank() == 0)
    fmt::print(stderr, "wheelset-table build: over MPI ranks the y grid is not refined where the contact jumps (the "
                       "default --refine-lateral-force-fraction {:g} needs one rank): give finer y steps in --y-m where "
                       "the flange snaps in\n",
               kWheelsetTableRefinementDefault);
  require(a.runtime_elements >= 20 && a.runtime_elements <= 100000, [&] {
    return fmt::format("--runtime-elements {} must lie in [20, 100000] (elements of the coarse patch FastSim runs on at "
                       "lookup)",
                       a.runtime_elements);
  });
  options.runtime_elements = a.runtime_elements;
  return options;
}

// A progress line at every tenth of the nodes and for every gap, with the time left.
void report_progress(const WheelsetTableProgress& p, std::chrono::steady_clock::time_point start,
                     std::size_t& next_report) {
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double left = elapsed / static_cast<double>(p.nodes_done) * static_cast<double>(p.nodes_total - p.nodes_done);
  const WheelsetTableNode& n = *p.node;
  if (n.status != WheelsetTableNodeStatus::solved)
    fmt::print(std::cerr, "  node {}/{} at y = {:+.3f} mm, yaw {:g} mrad, {:g} kN is a gap: {}\n", p.nodes_done,
               p.nodes_total, n.y_m * 1e3, n.yaw_rad * 1e3, n.wheel_load_N * 1e-3, n.message);
  if (p.nodes_done >= next_report || p.nodes_done == p.nodes_total) {
    fmt::print(std::cerr, "  [{:>3.0f} %] {}/{} nodes, {:.0f} s, about {:.0f} s left\n",
               100.0 * static_cast<double>(p.nodes_done) / static_cast<double>(p.nodes_total), p.nodes_done,
               p.nodes_total, elapsed, left);
    next_report = p.nodes_done + std::max<std::size_t>(1, p.nodes_total / 10);
  }
}

// What the table written holds: profiles, axes, nodes, gaps and patches, the build's time.
void print_table_summary(const BuildArguments& a, const WheelsetCase& c, const WheelsetTableGrid& grid,
                         const WheelsetTable& table, double seconds) {
  std::size_t gaps = 0, patches = 0;
  for (const WheelsetTableNode& n : table.nodes()) {
    gaps += n.status != WheelsetTableNodeStatus::solved;
    patches += n.wheels[0].size() + n.wheels[1].size();
  }
  fmt::print("Wheelset table {}\n", a.out);
  fmt::print("  profiles  {}\n", c.source.empty() ? std::string("S1002 / UIC60 1:40 (the shipped set-up)") : c.source);
  fmt::print("  y         {:+.3f} ... {:+.3f} mm, {} values\n", grid.y_m.front() * 1e3, grid.y_m.back() * 1e3, grid.y_m.size());
  fmt::print("  yaw       {:+g} ... {:+g} mrad, {} value(s){}\n", grid.yaw_rad.front() * 1e3, grid.yaw_rad.back() * 1e3,
             grid.yaw_rad.size(), grid.yaw_rad.size() == 1 ? " (every yaw served by turning the contact point)" : "");
  std::string loads;
  for (double load : grid.wheel_load_N) loads += fmt::format("{}{:g}", loads.empty() ? "" : ", ", load * 1e-3);
  fmt::print("  loads     {} kN per wheel\n", loads);
  fmt::print("  nodes     {} ({} gaps), {} patches, built in {:.1f} s ({:.3f} s per node)\n", table.nodes().size(), gaps,
             patches, seconds, seconds / static_cast<double>(table.nodes().size()));
}

// `railcontact wheelset-table build`: the grid and options checked, the output checked before the
// work, the nodes solved (shared among MPI ranks), the table written by rank 0.
int run_build(const BuildArguments& a, const CLI::App& sub) {
  require(!a.out.empty(), "wheelset-table build: --out must name the table file to write");
  const int threads = build_threads(a);
  const bool rank0 = study::MpiWorld::rank() == 0;
  WheelsetCase c;
  if (!a.case_file.empty()) c = read_wheelset_case(a.case_file);
  const WheelsetTableGrid grid = table_grid(a);
  WheelsetTableOptions options = table_options(a, sub, c);
  const WheelsetTrack track = wheelset_track(c);
  const std::filesystem::path out(a.out);
  if (rank0) check_table_writable(out, "wheelset table");  // before the work
  options.runner = study::table_node_runner(threads);
  options.created_utc = source_date_epoch_utc();

  if (rank0)
    fmt::print(std::cerr,
               "wheelset-table build: {} y values x {} yaw(s) x {} load(s) = {} nodes, elements {:g} mm, {} surface, {} "
               "thread(s){}\n",
               grid.y_m.size(), grid.yaw_rad.size(), grid.wheel_load_N.size(), grid.size(),
               options.wheelset.element_size_m * 1e3, contact_surface_name(options.wheelset.contact_surface), threads,
               study::MpiWorld::several() ? fmt::format(" on each of {} MPI ranks", study::MpiWorld::size()) : "");
  const auto start = std::chrono::steady_clock::now();
  std::size_t next_report = 0;
  const auto report = [&](const WheelsetTableProgress& p) { report_progress(p, start, next_report); };
  WheelsetTable table;
  try {
    table = build_wheelset_table(track, grid, options, report);
  } catch (const study::WorkerRankDone&) {
    return 0;  // an MPI rank other than 0: its share is computed, rank 0 writes the table
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  write_table_atomically(out, "wheelset table", [&](const std::filesystem::path& path) { save_wheelset_table(table, path); });
  print_table_summary(a, c, grid, table, seconds);
  return 0;
}

}  // namespace

void add_wheelset_table_command(CLI::App& app, Action& action) {
  CLI::App* command = app.add_subcommand(
      "wheelset-table", "The wheelset table: a wheelset's contact over y, yaw and wheel load, for evaluations in "
                        "microseconds (docs/WHEELSET_TABLE.md; use it with `railcontact wheelset --table FILE`)");
  command->require_subcommand(1);
  auto args = std::make_shared<BuildArguments>();
  CLI::App* build = command->add_subcommand("build", "build a wheelset table and write it to --out");
  build->add_option("case", args->case_file,
                    "wheelset case file (TOML, docs/CASE_FILES.md): its profiles, track, material, mesh; default "
                    "S1002/UIC60");
  build->add_option("--out", args->out, "the table file to write (JSON)")->required();
  build->add_option("--y-m", args->y_m, "lateral displacements FROM:TO:STEP (m, + to the left)")->capture_default_str();
  build->add_option("--yaw-rad", args->yaw_rad,
                    "yaw angles FROM:TO:STEP (rad, + the axle's left end backwards); one value serves every yaw")
      ->capture_default_str();
  build->add_option("--load-N", args->loads_N, "vertical loads per wheel (N, > 0; repeat or list)")
      ->capture_default_str()
      ->delimiter(',');
  build->add_option("--element-size-m", args->element_size_m, "element size of the contact meshes (m)")
      ->capture_default_str();
  build->add_option("--reference-weighting", args->reference_weighting,
                    "the nodes' reference points: squared-gap (default, as Kalker's CONTACT) or depth (docs/WHEELSET.md "
                    "§4); recorded in the table");
  build->add_option("--contact-surface", args->contact_surface,
                    "the nodes' contact surface: planar (default), conformal or auto (docs/WHEELSET.md §4); recorded in "
                    "the table, and a lookup asks for the same");
  build->add_option("--refine-lateral-force-fraction", args->refine_lateral_force,
                    "halve the y steps (up to three times, to 0.0125 mm) around a node whose wheel's lateral normal "
                    "force lies further than this fraction of its load from the line between its neighbours: a flange "
                    "snapping in, a second contact appearing (docs/WHEELSET_TABLE.md §3; 0: off; not over MPI ranks)")
      ->capture_default_str();
  build->add_option("--threads", args->threads,
                    "threads (a whole number >= 1; default: all cores, 1 per MPI rank); the table is the same on any "
                    "number");
  build->add_option("--runtime-elements", args->runtime_elements,
                    "elements of the coarse copy of each patch FastSim runs on at lookup: the lookup's cost against "
                    "FastSim's discretisation error (docs/WHEELSET_TABLE.md §3)")
      ->capture_default_str();
  build->callback([args, build, &action] { action = [args, build] { return run_build(*args, *build); }; });
}

}  // namespace railcontact::cli
