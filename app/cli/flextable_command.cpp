// `railcontact flextable build|check`: the flexibility table of a profile pair (docs/FLEXTABLE.md).
#include <fmt/core.h>
#include <fmt/ostream.h>

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cli/commands.hpp"
#include "cli/note_on_success.hpp"
#include "cli/flextable_shards.hpp"
#include "cli/table_file_output.hpp"
#include "railcontact/error.hpp"
#include "railcontact/flexibility_table.hpp"
#include "railcontact/version.h"
#include "study/case_pool.hpp"
#include "study/flexibility_table_check.hpp"
#include "study/mpi_cases.hpp"
#include "study/sweep_journal.hpp"

namespace railcontact::cli {
namespace {

constexpr double kMm = 1e-3;

struct BuildArguments {
  std::string out;
  double y_from_m = -4.5e-3;
  double y_to_m = 4.5e-3;
  double y_step_m = 0.25e-3;
  std::vector<double> loads_N{98100.0};
  std::optional<std::string> wheel;
  std::optional<std::string> rail;
  int elements = 3000;
  int flexibility_coarsening = 0;
  std::string threads;
  std::string shard;
  bool restart = false;
  std::optional<std::string> created_utc;  // merge: the shards' (else SOURCE_DATE_EPOCH's, or now)
};

// A shard's part of a build is in its journal: the build stops there (the table is merge's).
struct ShardDone {
  std::filesystem::path journal;
  std::size_t computed = 0, resumed = 0;
};

// The arguments of a build as recorded in a shard's journal (and the profiles' fingerprints):
// merge rebuilds the table's grid, metadata and contact jumps from them.
std::string build_recipe(const BuildArguments& a, const WheelRailPair& pair) {
  study::TableShardRecipe r;
  r.y_from_m = a.y_from_m;
  r.y_to_m = a.y_to_m;
  r.y_step_m = a.y_step_m;
  r.loads_N = a.loads_N;
  r.wheel = a.wheel;
  r.rail = a.rail;
  r.elements = a.elements;
  r.flexibility_coarsening = a.flexibility_coarsening;
  r.wheel_profile_fnv1a64 = file_fingerprint(pair.wheel().source()).hash_hex();
  r.rail_profile_fnv1a64 = file_fingerprint(pair.rail().source()).hash_hex();
  r.created_utc = source_date_epoch_utc();
  return study::table_shard_metadata(r);
}

struct CheckArguments {
  std::string table;
  std::optional<std::string> wheel;
  std::optional<std::string> rail;
  std::vector<double> y_m;
  std::vector<double> loads_N;
  double mu = 0.3;
  int elements = 0;
  std::string interpolation = "area-scaled";
  bool json = false;
  bool exact = false;
};

WheelRailPair pair_of(const std::optional<std::string>& wheel, const std::optional<std::string>& rail) {
  return load_wheel_rail_pair(wheel ? std::filesystem::path(*wheel) : default_wheel_profile_path(),
                              rail ? std::filesystem::path(*rail) : default_rail_profile_path());
}

void print_nodes(const FlexibilityTable& table) {
  fmt::print("\n{:>9} {:>9} {:>15} {:>8} {:>9} {:>11} {:>11} {:>11} {:>10} {:>10} {:>10} {:>8}\n", "y (mm)", "Fz (kN)",
             "status", "elements", "area mm2", "L1 (m/Pa)", "L2 (m/Pa)", "L3 (m/Pa)", "f11 (MN)", "f22 (MN)",
             "f23 (kN m)", "spin 1/m");
  for (const FlexibilityTableNode& n : table.nodes()) {
    fmt::print("{:>+9.4f} {:>9.2f} {:>15}", n.y_m / kMm, n.vertical_load_N * 1e-3, flexibility_node_status_name(n.status));
    if (n.status == FlexibilityNodeStatus::solved)
      fmt::print(" {:>8} {:>9.2f} {:>11.4e} {:>11.4e} {:>11.4e} {:>10.4f} {:>10.4f} {:>10.4f} {:>8.4f}", n.elements_in_contact,
                 n.area_m2 * 1e6, n.flexibility.L1, n.flexibility.L2, n.flexibility.L3, n.f11_N * 1e-6, n.f22_N * 1e-6,
                 n.f23_Nm * 1e-3, n.spin_per_m);
    else
      fmt::print("  {}", n.message);
    fmt::print("\n");
  }
}

// --load-N checked (each a wheel load, the values different, not too many) and sorted.
std::vector<double> checked_loads(const BuildArguments& args) {
  for (double load : args.loads_N) {
    require(std::isfinite(load) && load > 0.0, [&] { return fmt::format("--load-N must be positive (got {} N)", load); });
    validate_normal_force(load, "--load-N");
  }
  std::vector<double> loads = args.loads_N;
  std::sort(loads.begin(), loads.end());
  require(std::adjacent_find(loads.begin(), loads.end()) == loads.end(), "--load-N values must differ");
  require(loads.size() <= kMaximumFlexibilityTableLoads, [&] {
    return fmt::format("--load-N: {} loads; a table holds at most {}", loads.size(), kMaximumFlexibilityTableLoads);
  });
  return loads;
}

// --y-from-m and --y-to-m within the lateral displacements a wheel stays on its rail.
void check_y_range(const BuildArguments& args) {
  for (const auto& [option, value] : {std::pair{"--y-from-m", args.y_from_m}, std::pair{"--y-to-m", args.y_to_m}})
    require(std::abs(value) <= kMaximumWheelRailLateralDisplacement_m, [&] {
      return fmt::format("{} {:g} m must lie in [{:g}, {:g}] m (a lateral displacement in metres: beyond it the wheel "
                         "is off its rail)",
                         option, value, -kMaximumWheelRailLateralDisplacement_m, kMaximumWheelRailLateralDisplacement_m);
    });
}

// The build's options: the patches' mesh, nH-FastSim's coarsening, the nodes on threads (and
// ranks), the table's date.
FlexibilityTableOptions build_options(const BuildArguments& args, int threads) {
  FlexibilityTableOptions options;
  options.patch.target_elements = args.elements;
  require(args.flexibility_coarsening >= 0 && args.flexibility_coarsening <= kMaximumCoarsening, [&] {
    return fmt::format("flextable build: --flexibility-coarsening {} must lie in [0, {}] (0: automatic)",
                       args.flexibility_coarsening, kMaximumCoarsening);
  });
  options.nh_fastsim.flexibility_coarsening = args.flexibility_coarsening;
  options.runner = study::table_node_runner(threads);
  options.created_utc = args.created_utc ? *args.created_utc : source_date_epoch_utc();
  return options;
}

// The nodes a shard's journal holds from an earlier run (read on rank 0 only; --restart discards
// them first). A journal of another build is refused.
struct ShardResume {
  std::map<std::size_t, study::CaseResult> done;
  bool exists = false;
  std::uintmax_t valid_bytes = 0;  // where the journal's complete records end: appended from there
};

ShardResume resume_shard(const std::filesystem::path& journal, const study::SweepJournalHeader& header,
                         std::size_t count, const study::Shard& shard, bool restart) {
  ShardResume resume;
  if (study::MpiWorld::rank() != 0) return resume;
  if (restart) std::filesystem::remove(journal);
  if (!std::filesystem::exists(journal)) return resume;
  study::SweepJournal j = study::read_sweep_journal(journal, study::kResumeAdvice);
  require(j.header.recipe == header.recipe && j.header.cases == count && j.header.shard.index == shard.index &&
              j.header.shard.count == shard.count && j.header.version == header.version,
          [&] {
            return fmt::format("{} holds {} nodes of another build (the arguments, profiles or railcontact "
                               "changed); rerun with --restart to discard them",
                               journal.string(), j.done.size());
          });
  resume.done = std::move(j.done);
  resume.exists = true;
  resume.valid_bytes = j.valid_bytes;
  return resume;
}

// A shard's runner: its nodes (on threads or ranks) into its journal, resumed when it exists; it
// ends the build with ShardDone (WorkerRankDone on the ranks other than 0).
TableNodeRunner shard_runner(const BuildArguments& args, const study::Shard& shard, const WheelRailPair& pair,
                             int threads) {
  const std::string recipe = build_recipe(args, pair);
  const std::filesystem::path journal = fmt::format("{}.shard-{}-of-{}.journal", args.out, shard.index, shard.count);
  return [=, &args](std::size_t count, const TableNodeSolver& solve, const TableNodeStore&) {
    study::SweepJournalHeader header{RC_VERSION_STRING, study::hash_hex(recipe), count, shard, recipe, ""};
    const ShardResume resume = resume_shard(journal, header, count, shard, args.restart);
    std::vector<std::size_t> todo;
    for (std::size_t k = shard.index; k < count; k += shard.count)
      if (!resume.done.contains(k)) todo.push_back(k);
    std::optional<study::SweepJournalWriter> writer;
    if (study::MpiWorld::rank() == 0) writer.emplace(journal, header, resume.exists, resume.valid_bytes);
    const study::CaseWorkerFactory factory = [&solve]() -> study::CaseWorker {
      return [&solve](std::size_t k) { return study::CaseResult{solve(k), false}; };
    };
    study::ProgressLine line(std::cerr, "nodes", todo.size());
    std::size_t computed = 0;
    study::run_cases_on_ranks(todo, threads, factory, [&](std::size_t k, study::CaseResult&& r) {
      writer->append(k, r);
      line.done(++computed);
    });
    if (study::MpiWorld::rank() != 0) throw study::WorkerRankDone{};
    writer->close();
    throw ShardDone{journal, computed, resume.done.size()};
  };
}

// One progress line per node with the estimated time left (from the mean time per node so far).
void report_node(const FlexibilityTableProgress& p, std::chrono::steady_clock::time_point start) {
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double left = elapsed / static_cast<double>(p.nodes_done) * static_cast<double>(p.nodes_total - p.nodes_done);
  const FlexibilityTableNode& n = *p.node;
  if (n.status == FlexibilityNodeStatus::solved)
    fmt::print(std::cerr, "  node {}/{}: y = {:+.4f} mm, Fz = {:g} N: {} elements, {:.2f} s; {:.1f} s left\n",
               p.nodes_done, p.nodes_total, n.y_m / kMm, n.vertical_load_N, n.elements_in_contact, p.node_seconds, left);
  else
    fmt::print(std::cerr, "  node {}/{}: y = {:+.4f} mm, Fz = {:g} N: {} ({}), a gap in the table; {:.1f} s left\n",
               p.nodes_done, p.nodes_total, n.y_m / kMm, n.vertical_load_N, flexibility_node_status_name(n.status),
               n.message, left);
}

// What the table written holds: the profiles, the y values (the grid's and those bracketing a
// contact jump), the loads, the nodes by status, the material; then every node.
void print_build_summary(const BuildArguments& args, const FlexibilityTable& table, const std::vector<double>& y,
                         const std::vector<double>& loads, double seconds) {
  const FlexibilityTableMetadata& m = table.metadata();
  std::size_t solved = 0, several = 0, failed = 0;
  for (const FlexibilityTableNode& n : table.nodes()) {
    solved += n.status == FlexibilityNodeStatus::solved;
    several += n.status == FlexibilityNodeStatus::several_patches;
    failed += n.status == FlexibilityNodeStatus::failed;
  }
  fmt::print("Flexibility table {}\n", args.out);
  fmt::print("  wheel    {} (fnv1a64 {})\n  rail     {} (fnv1a64 {})\n", m.wheel_profile.file,
             m.wheel_profile.hash_hex(), m.rail_profile.file, m.rail_profile.hash_hex());
  fmt::print("  y        {:.4f} ... {:.4f} mm: {} values ({} from the grid, {} bracketing {} contact jump(s))\n",
             table.y_m().front() / kMm, table.y_m().back() / kMm, table.y_m().size(), y.size(), table.y_m().size() - y.size(),
             table.contact_jumps().size());
  for (const ContactJump& j : table.contact_jumps())
    fmt::print("  jump     between y = {:.4f} and {:.4f} mm (first touch on the rail {:.2f} -> {:.2f} mm)\n",
               table.y_m()[j.interval] / kMm, table.y_m()[j.interval + 1] / kMm, j.y_rail_left_m / kMm, j.y_rail_right_m / kMm);
  std::string load_list;
  for (double load : loads) load_list += fmt::format("{}{:g}", load_list.empty() ? "" : ", ", load);
  fmt::print("  Fz       {} N\n", load_list);
  fmt::print("  nodes    {} solved, {} with several patches, {} failed (gaps: lookups next to them are refused)\n", solved,
             several, failed);
  fmt::print("  material E = {:g} Pa, nu = {:g}; about {} elements in contact; built in {:.1f} s\n",
             m.material.youngs_modulus_Pa, m.material.poisson_ratio, m.target_elements, seconds);
  print_nodes(table);
}

// `railcontact flextable build` (and `merge`, with the shards' nodes): the arguments and the output
// checked before the work, the nodes solved here, in a shard or taken from the shards, the table
// written by rank 0.
int run_build(const BuildArguments& args, const std::map<std::size_t, study::CaseResult>* merged = nullptr) {
  // Every core by default (one thread per rank under mpirun); the table does not depend on it.
  const int threads = args.threads.empty() ? (study::MpiWorld::several() ? 1 : study::available_cores())
                                           : study::parse_threads(args.threads);
  require(!args.out.empty(), "--out must name the table file to write");
  require(args.elements >= kMinimumWheelRailElements && args.elements <= kMaximumWheelRailElements, [&] {
    return fmt::format("--elements {} must lie in [{}, {}] (with fewer, the elements are too large for the patch and "
                       "the profiles)",
                       args.elements, kMinimumWheelRailElements, kMaximumWheelRailElements);
  });
  const std::vector<double> loads = checked_loads(args);
  check_y_range(args);
  const std::vector<double> y = flexibility_table_y_grid(args.y_from_m, args.y_to_m, args.y_step_m);
  // The work of the build (nodes × elements), refused before the profiles are read.
  check_flexibility_table_work(y.size(), loads.size(), args.elements);
  const WheelRailPair pair = pair_of(args.wheel, args.rail);
  // Fail on an unwritable output before the work: create (and remove) a file next to it.
  const std::filesystem::path out(args.out);
  const bool rank0 = study::MpiWorld::rank() == 0;
  if (rank0) check_table_writable(out, "flexibility table");

  FlexibilityTableOptions options = build_options(args, threads);
  const study::Shard shard = args.shard.empty() ? study::Shard{} : study::parse_shard(args.shard);
  if (merged != nullptr) {
    // merge: the nodes come from the shards' journals.
    options.runner = study::merged_node_runner(*merged);
  } else if (!shard.whole()) {
    options.runner = shard_runner(args, shard, pair, threads);
  }
  if (rank0)
    fmt::print(std::cerr, "flextable build: {} y values x {} load(s), about {} elements in contact, {} thread(s){}\n",
               y.size(), loads.size(), args.elements, threads,
               study::MpiWorld::several() ? fmt::format(" on each of {} MPI ranks", study::MpiWorld::size()) : "");
  const auto start = std::chrono::steady_clock::now();
  const auto report = [&](const FlexibilityTableProgress& p) { report_node(p, start); };
  FlexibilityTable table;
  try {
    table = build_flexibility_table(pair, y, loads, options, report);
  } catch (const study::WorkerRankDone&) {
    return 0;  // an MPI rank other than 0: its share is computed, rank 0 writes the table
  } catch (const ShardDone& done) {
    fmt::print("Wrote {} (shard {}/{}: {} nodes computed, {} from an earlier run); combine the shards with "
               "`railcontact merge`\n",
               done.journal.string(), shard.index, shard.count, done.computed, done.resumed);
    return 0;
  }
  for (const ContactJump& j : table.contact_jumps())
    fmt::print(std::cerr, "  contact jump between y = {:.4f} and {:.4f} mm (first touch on the rail {:.2f} -> {:.2f} mm)\n",
               table.y_m()[j.interval] / kMm, table.y_m()[j.interval + 1] / kMm, j.y_rail_left_m / kMm,
               j.y_rail_right_m / kMm);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  write_table_atomically(out, "flexibility table", [&](const std::filesystem::path& path) { save_flexibility_table(table, path); });
  print_build_summary(args, table, y, loads, seconds);
  return 0;
}

// The check's options from the arguments (checked by the check itself).
study::FlexibilityTableCheckOptions check_options(const CheckArguments& args) {
  study::FlexibilityTableCheckOptions options;
  options.y_m = args.y_m;
  options.vertical_loads_N = args.loads_N;
  options.mu = args.mu;
  options.target_elements = args.elements;
  options.interpolation =
      args.interpolation == "plain" ? FlexibilityInterpolation::plain : FlexibilityInterpolation::area_scaled;
  options.against_exact = args.exact;
  return options;
}

// --json: per point both flexibilities and the families' force differences (with --exact also
// against the exact solver).
nlohmann::json check_points_json(const study::FlexibilityTableCheck& check, bool exact) {
  nlohmann::json points = nlohmann::json::array();
  for (const auto& p : check.points) {
    points.push_back({{"y_m", p.y_m},
                      {"vertical_load_N", p.vertical_load_N},
                      {"elements_in_contact", p.elements_in_contact},
                      {"flexibility_on_the_fly", {p.on_the_fly.L1, p.on_the_fly.L2, p.on_the_fly.L3}},
                      {"flexibility_table", {p.table.L1, p.table.L2, p.table.L3}},
                      {"f11_on_the_fly_N", p.f11_on_the_fly_N},
                      {"f22_on_the_fly_N", p.f22_on_the_fly_N},
                      {"f11_table_N", p.f11_table_N},
                      {"f22_table_N", p.f22_table_N},
                      {"force_difference", p.force_difference},
                      {"force_difference_table_normalised", p.force_difference_table_normalised}});
    if (exact) {
      points.back()["table_error_against_exact"] = p.table_error_against_exact;
      points.back()["on_the_fly_error_against_exact"] = p.on_the_fly_error_against_exact;
    }
  }
  return points;
}

// --json: one object with the points, the skipped ones and the statistics.
void print_check_json(const CheckArguments& args, const study::FlexibilityTableCheck& check, double seconds) {
  const study::FlexibilityTableCheckPoint& worst = check.points[check.max_point];
  nlohmann::json families = nlohmann::json::array();
  for (const auto& f : check.families) families.push_back(f.name);
  nlohmann::json out = {{"railcontact_version", RC_VERSION_STRING},
                        {"table", args.table},
                        {"interpolation", args.interpolation},
                        {"mu", args.mu},
                        {"families", families},
                        {"points", check_points_json(check, args.exact)},
                        {"skipped", check.skipped},
                        {"max_force_difference", check.max_force_difference},
                        {"max_at", {{"y_m", worst.y_m},
                                    {"vertical_load_N", worst.vertical_load_N},
                                    {"family", check.families[check.max_family].name}}},
                        {"mean_force_difference", check.mean_force_difference},
                        {"max_force_difference_table_normalised", check.max_force_difference_table_normalised},
                        {"mean_force_difference_table_normalised", check.mean_force_difference_table_normalised},
                        {"time_s", seconds}};
  if (args.exact) {
    out["max_table_error_against_exact"] = check.max_table_error_against_exact;
    out["mean_table_error_against_exact"] = check.mean_table_error_against_exact;
    out["max_on_the_fly_error_against_exact"] = check.max_on_the_fly_error_against_exact;
    out["mean_on_the_fly_error_against_exact"] = check.mean_on_the_fly_error_against_exact;
  }
  fmt::print("{}\n", out.dump(2));
}

// One line per point: the table's flexibilities against on-the-fly ones and the families' force
// differences (%); then the points skipped.
void print_check_points(const study::FlexibilityTableCheck& check) {
  fmt::print("{:>43}  |F_table - F_onthefly| / |F_onthefly| (%)\n", "");
  fmt::print("{:>9} {:>8} {:>8} {:>7} {:>7} {:>7} ", "y (mm)", "Fz (kN)", "elements", "dL1 %", "dL2 %", "dL3 %");
  for (const auto& f : check.families) fmt::print(" {:>17}", f.name);
  fmt::print("\n");
  for (const auto& p : check.points) {
    fmt::print("{:>+9.4f} {:>8.2f} {:>8} {:>+7.3f} {:>+7.3f} {:>+7.3f} ", p.y_m / kMm, p.vertical_load_N * 1e-3,
               p.elements_in_contact, 100 * (p.table.L1 / p.on_the_fly.L1 - 1), 100 * (p.table.L2 / p.on_the_fly.L2 - 1),
               100 * (p.table.L3 / p.on_the_fly.L3 - 1));
    for (double d : p.force_difference) fmt::print(" {:>17.3f}", 100 * d);
    fmt::print("\n");
  }
  for (const std::string& s : check.skipped) fmt::print("skipped: {}\n", s);
}

// The check as text: the heading, the points, the largest and mean differences and the target.
void print_check_text(const CheckArguments& args, const study::FlexibilityTableCheck& check, double seconds) {
  const study::FlexibilityTableCheckPoint& worst = check.points[check.max_point];
  fmt::print("Flexibility table {}: nH-FastSim forces with the table's flexibilities against on-the-fly (K2) ones\n",
             args.table);
  fmt::print("  the same patch per point; the same raw creepages (xi, eta from the on-the-fly f11, f22); mu = {:g}; "
             "interpolation {}\n\n",
             args.mu, args.interpolation);
  print_check_points(check);
  fmt::print("\nmax |F_table - F_onthefly| / |F_onthefly| = {:.3f} % at y = {:+.4f} mm, Fz = {:g} N, {}; mean {:.3f} % "
             "({} points x {} families)\n",
             100 * check.max_force_difference, worst.y_m / kMm, worst.vertical_load_N,
             check.families[check.max_family].name, 100 * check.mean_force_difference, check.points.size(),
             check.families.size());
  fmt::print("with the table's own normalisation (as run --flextable): max {:.3f} %, mean {:.3f} %\n",
             100 * check.max_force_difference_table_normalised, 100 * check.mean_force_difference_table_normalised);
  if (args.exact)
    fmt::print("against exact (|F - F_exact| / |F_exact|): the table max {:.3f} %, mean {:.3f} %; on the fly max {:.3f} %, "
               "mean {:.3f} %\n",
               100 * check.max_table_error_against_exact, 100 * check.mean_table_error_against_exact,
               100 * check.max_on_the_fly_error_against_exact, 100 * check.mean_on_the_fly_error_against_exact);
  fmt::print("target < 0.5 %: {}; checked in {:.1f} s\n", check.max_force_difference < 0.005 ? "met" : "NOT met", seconds);
}

// `railcontact flextable check`: the table against on-the-fly nH-FastSim on the profiles (progress
// on stderr unless --json), printed as text or one JSON object.
int run_check(const CheckArguments& args) {
  const FlexibilityTable table = load_flexibility_table(args.table);
  const std::string recipe_note = older_nh_fastsim_recipe_note(table.metadata().nh_fastsim_recipe);
  const NoteOnSuccess note(recipe_note.empty() ? recipe_note : args.table + ": " + recipe_note);
  const WheelRailPair pair = pair_of(args.wheel, args.rail);
  const study::FlexibilityTableCheckOptions options = check_options(args);
  const auto start = std::chrono::steady_clock::now();
  const study::FlexibilityTableCheck check =
      study::check_flexibility_table(table, pair, options, args.json ? nullptr : &std::cerr);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (args.json)
    print_check_json(args, check, seconds);
  else
    print_check_text(args, check, seconds);
  return 0;
}

}  // namespace

int merge_flextable_shards(const study::SweepJournalHeader& header, const std::filesystem::path& journal,
                           const std::map<std::size_t, study::CaseResult>& nodes, const std::string& out) {
  const study::TableShardRecipe recipe = study::table_shard_recipe(header, journal);
  BuildArguments args;
  args.out = out;
  args.y_from_m = recipe.y_from_m;
  args.y_to_m = recipe.y_to_m;
  args.y_step_m = recipe.y_step_m;
  args.loads_N = recipe.loads_N;
  args.wheel = recipe.wheel;
  args.rail = recipe.rail;
  args.elements = recipe.elements;
  args.flexibility_coarsening = recipe.flexibility_coarsening;
  args.threads = "1";
  args.created_utc = recipe.created_utc;
  // The profiles here must be those the shards were built from.
  const WheelRailPair pair = pair_of(args.wheel, args.rail);
  require(file_fingerprint(pair.wheel().source()).hash_hex() == recipe.wheel_profile_fnv1a64 &&
              file_fingerprint(pair.rail().source()).hash_hex() == recipe.rail_profile_fnv1a64,
          [&] {
            return fmt::format("merge: the profiles {} and {} here are not those the shards were built from",
                               pair.wheel().source(), pair.rail().source());
          });
  return run_build(args, &nodes);
}

void add_flextable_command(CLI::App& app, Action& action) {
  CLI::App* flextable = app.add_subcommand("flextable", "flexibility table of a profile pair: build it, check its accuracy");
  flextable->require_subcommand(1);

  auto build = std::make_shared<BuildArguments>();
  CLI::App* b = flextable->add_subcommand("build", "precompute nH-FastSim's L1-L3 and f11, f22, f23 over y (and Fz)");
  b->add_option("--out", build->out, "table file to write (JSON, docs/FLEXTABLE.md)")->required();
  b->add_option("--y-from-m", build->y_from_m, "first wheelset displacement (m, + to the left)")->capture_default_str();
  b->add_option("--y-to-m", build->y_to_m, "last wheelset displacement (m, + to the left)")->capture_default_str();
  b->add_option("--y-step-m", build->y_step_m, "step of the displacement (m, > 0)")->capture_default_str();
  b->add_option("--load-N", build->loads_N, "vertical wheel load(s) Fz (N, > 0); several give a load axis")
      ->capture_default_str();
  b->add_option("--wheel", build->wheel, "wheel profile file (default: the shipped S1002)");
  b->add_option("--rail", build->rail, "rail profile file (default: the shipped UIC60 1:40)");
  b->add_option("--elements", build->elements, "about this many elements in contact")->capture_default_str();
  b->add_option("--flexibility-coarsening", build->flexibility_coarsening,
                "nH-FastSim's K2 on the patch coarsened in square blocks of this factor (0: automatic, as `run`; 1: the patch itself)")
      ->capture_default_str();
  b->add_option("--threads", build->threads,
                "threads (a whole number >= 1; default: all cores, 1 per MPI rank); the table is the same on any number");
  b->add_option("--shard", build->shard,
                "compute shard i of N only (nodes k with k mod N = i) into OUT.shard-i-of-N.journal, for `railcontact merge`");
  b->add_flag("--restart", build->restart, "with --shard: discard the nodes of an earlier run of this shard");
  b->callback([build, &action] { action = [build] { return run_build(*build); }; });

  auto check = std::make_shared<CheckArguments>();
  CLI::App* c = flextable->add_subcommand(
      "check", "force error of the table against on-the-fly flexibilities between its nodes (the paper's creepages)");
  c->add_option("--table", check->table, "flexibility table file")->required();
  c->add_option("--wheel", check->wheel, "wheel profile file (default: the shipped S1002)");
  c->add_option("--rail", check->rail, "rail profile file (default: the shipped UIC60 1:40)");
  c->add_option("--y-m", check->y_m,
                "check at these wheelset displacements y (m, + to the left; default: the midpoints between the table's "
                "nodes)");
  c->add_option("--load-N", check->loads_N,
                "check at these vertical loads Fz (N, > 0; default: the table's loads and their geometric midpoints)");
  c->add_option("--mu", check->mu, "friction coefficient (dimensionless)")->capture_default_str();
  c->add_option("--elements", check->elements, "elements in contact of the check patches (default: the table's)");
  c->add_option("--interpolation", check->interpolation, "area-scaled (the table's lookup) or plain (L and f themselves)")
      ->check(CLI::IsMember({"area-scaled", "plain"}))
      ->capture_default_str();
  c->add_flag("--json", check->json, "print one JSON object");
  c->add_flag("--exact", check->exact, "also the error of the table and of on-the-fly nH-FastSim against the exact solver");
  c->callback([check, &action] { action = [check] { return run_check(*check); }; });
}

}  // namespace railcontact::cli
