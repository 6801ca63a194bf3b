// `railcontact sweep` and `railcontact merge` (see the header).
#include "study/sweep_run.hpp"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <cerrno>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <tuple>

#include "railcontact/flexibility_table.hpp"
#include "railcontact/version.h"
#include "railcontact/wheelset.hpp"
#include "output/figures.hpp"
#include "study/mpi_cases.hpp"
#include "output/output_directory.hpp"
#include "study/sweep_journal.hpp"

namespace railcontact::study {
namespace {

// The input columns of every row: the state values a sweep may set (wheel_load_N as the two
// wheels' loads; empty when the wheelset is by position).
constexpr const char* kInputColumns[] = {"y_mm",
                                         "yaw_mrad",
                                         "roll_mrad",
                                         "z_mm",
                                         "speed_m_per_s",
                                         "lateral_velocity_m_per_s",
                                         "vertical_velocity_m_per_s",
                                         "roll_rate_rad_per_s",
                                         "yaw_rate_rad_per_s",
                                         "extra_longitudinal_creepage",
                                         "right_wheel_N",
                                         "left_wheel_N",
                                         "mu"};

struct Recipe {
  std::string metadata;  // JSON text (the hash is over it)
  std::string header;    // CSV header line
  std::string hash;
};

nlohmann::json fingerprint_json(const std::string& source) {
  try {
    const FileFingerprint f = file_fingerprint(source);
    return {{"file", std::filesystem::path(source).filename().string()}, {"fnv1a64", f.hash_hex()}};
  } catch (const Error&) {
    return {{"file", std::filesystem::path(source).filename().string()}, {"fnv1a64", nullptr}};
  }
}

std::vector<std::string> columns(const SweepFile& s) {
  std::vector<std::string> c{"case", "status"};
  for (const char* k : kInputColumns) c.emplace_back(k);
  for (const char* k : {"side", "vertical_displacement_mm", "roll_solved_mrad", "patch", "patches", "reference_y_mm",
                        "rail_profile_y_mm", "wheel_profile_y_mm", "contact_angle_rad", "rolling_radius_mm", "xi", "eta",
                        "phi_per_m", "normal_force_N", "area_mm2", "max_pressure_MPa", "elements"})
    c.emplace_back(k);
  for (TangentialSolver solver : s.base.options.solvers)
    for (const char* f : {"F1_N", "F2_N", "M3_Nm"}) c.push_back(fmt::format("{}_{}", solver_name(solver), f));
  for (const char* k : {"wheel_Fx_N", "wheel_Fy_N", "wheel_Fz_N", "error_kind", "error"}) c.emplace_back(k);
  return c;
}

// The set-up file the track was read from (the sweep's [setup] file, or the default one, found
// through RAILCONTACT_DATA, when the sweep names no profiles); null when it names profiles.
nlohmann::json setup_json(const WheelsetCase& c) {
  if (!c.right_wheel_profile.empty()) return nullptr;
  return fingerprint_json((c.setup_file.empty() ? default_wheel_rail_setup_path() : c.setup_file).string());
}

Recipe make_recipe(const SweepFile& s, const WheelsetTrack& track) {
  const WheelsetOptions& o = s.base.options;
  const TrackWheelsetParameters& t = track.parameters();
  nlohmann::json solvers = nlohmann::json::array();
  for (TangentialSolver solver : o.solvers) solvers.push_back(solver_name(solver));
  nlohmann::json axes = nlohmann::json::array();
  for (const SweepAxis& a : s.axes) axes.push_back({{"key", a.key}, {"values", a.values}});
  const std::vector<std::string> cols = columns(s);
  nlohmann::json j = {
      {"railcontact_version", RC_VERSION_STRING},
      {"command", "sweep"},
      {"sweep_file", {{"file", std::filesystem::path(s.source).filename().string()},
                      {"fnv1a64", hash_hex(s.text)},
                      {"text", s.text}}},
      {"profiles",
       {{"right_wheel", fingerprint_json(track.pair(WheelSide::right).wheel().source())},
        {"right_rail", fingerprint_json(track.pair(WheelSide::right).rail().source())},
        {"left_wheel", fingerprint_json(track.pair(WheelSide::left).wheel().source())},
        {"left_rail", fingerprint_json(track.pair(WheelSide::left).rail().source())}}},
      // Everything else the numbers depend on: the set-up file's bytes and the track it gives.
      {"setup", setup_json(s.base)},
      {"track",
       {{"track_gauge_m", t.track_gauge_m},
        {"gauge_measuring_depth_m", t.gauge_measuring_depth_m},
        {"flange_back_distance_m", t.flange_back_distance_m},
        {"flange_back_y_m", t.flange_back_y_m},
        {"taping_line_from_flange_back_m", t.taping_line_from_flange_back_m},
        {"nominal_rolling_radius_m", t.nominal_rolling_radius_m}}},
      {"recipe",
       {{"solvers", solvers},
        {"by_load", o.loads.has_value()},
        {"balance_roll", o.loads ? o.loads->balance_roll : false},
        {"element_size_m", o.element_size_m},
        {"youngs_modulus_Pa", o.material.youngs_modulus_Pa},
        {"poisson_ratio", o.material.poisson_ratio},
        {"flexibility_coarsening", o.nh_fastsim.flexibility_coarsening},
        {"nh_fastsim_slip_direction", slip_direction_name(o.nh_fastsim.bound.slip_direction)},
        {"nh_fastsim_recipe", kNhFastSimRecipe},
        {"warm_start", "none: every case starts cold (results independent of the order, threads and ranks)"}}},
      {"kind", s.grid ? "grid" : "list"},
      {"axes", axes},
      {"varied", s.varied_keys()},
      {"cases", s.size()},
      {"csv", {{"file", "sweep.csv"},
               {"rows", "one per case and contact patch (right wheel first, each wheel's patches gauge side first); "
                        "a failed case: one row, status failed, with error_kind and error"},
               {"columns", cols}}},
  };
  Recipe r;
  r.metadata = j.dump(2);
  r.hash = hash_hex(r.metadata);
  for (std::size_t i = 0; i < cols.size(); ++i) r.header += (i ? "," : "") + cols[i];
  r.header += "\n";
  return r;
}

std::string csv_text(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += "\"\"";
    else if (c == '\n' || c == '\r') out += ' ';
    else out += c;
  }
  return out + "\"";
}

std::string input_fields(const SweepCase& c, bool by_load) {
  const WheelsetPosition& p = c.state.position;
  const WheelsetVelocity& v = c.state.velocity;
  return fmt::format("{:.10g},{:.10g},{:.10g},{},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{},{},{:.10g}",
                     p.lateral_displacement_m * 1e3, p.yaw_rad * 1e3, p.roll_rad * 1e3,
                     by_load ? std::string() : fmt::format("{:.10g}", p.vertical_displacement_m * 1e3),
                     v.forward_speed_m_per_s, v.lateral_velocity_m_per_s, v.vertical_velocity_m_per_s,
                     v.roll_rate_rad_per_s, v.yaw_rate_rad_per_s, v.extra_longitudinal_creepage,
                     c.loads ? fmt::format("{:.10g}", c.loads->right_N) : std::string(),
                     c.loads ? fmt::format("{:.10g}", c.loads->left_N) : std::string(), c.friction_coefficient);
}

}  // namespace

// One worker per thread: its own wheelset, rebuilt when the loads or the friction change (in a
// grid they are the outer axes), each case started cold.
CaseWorkerFactory sweep_worker_factory(const SweepFile& sweep, const WheelsetTrack& track) {
  return [&sweep, &track]() -> CaseWorker {
    // At most one wheelset per thread: its plans of the last case are all it keeps.
    auto wheelsets = std::make_shared<std::map<std::tuple<double, double, double>, Wheelset>>();
    const std::size_t solver_count = sweep.base.options.solvers.size();
    return [&sweep, &track, wheelsets, solver_count](std::size_t k) -> CaseResult {
      const SweepCase c = sweep.at(k);
      const bool by_load = c.loads.has_value();
      const std::string inputs = input_fields(c, by_load);
      try {
        WheelsetOptions options = sweep.base.options;
        options.loads = c.loads;
        options.friction_coefficient = c.friction_coefficient;
        const auto key = std::make_tuple(c.loads ? c.loads->right_N : 0.0, c.loads ? c.loads->left_N : 0.0,
                                         c.friction_coefficient);
        auto it = wheelsets->find(key);
        if (it == wheelsets->end()) {
          wheelsets->clear();
          it = wheelsets->emplace(key, Wheelset(track, options)).first;
        }
        Wheelset& wheelset = it->second;
        wheelset.reset_warm_start();  // every case cold: the same numbers in any order
        const WheelsetResult r = wheelset.evaluate(c.state);
        std::string rows;
        for (const WheelResult& w : r.wheels) {
          for (std::size_t p = 0; p < w.patches.size(); ++p) {
            const WheelsetPatch& patch = w.patches[p];
            const InterpenetrationRegion& g = patch.region;
            rows += fmt::format("{},ok,{},{},{:.6f},{:.6f},{},{},{:.6f},{:.6f},{:.6f},{:.8f},{:.6f},{:.8e},{:.8e},{:.8e},"
                                "{:.3f},{:.6f},{:.3f},{}",
                                k, inputs, side_name(w.side), w.vertical_displacement_m * 1e3,
                                r.state.position.roll_rad * 1e3, p, w.patches.size(), g.reference_point_track_m[1] * 1e3,
                                g.rail_profile_y_m * 1e3, g.wheel_profile_y_m * 1e3, g.contact_angle_rad,
                                patch.rolling_radius_m * 1e3, patch.creepage.xi, patch.creepage.eta, patch.creepage.phi,
                                patch.normal_force_N, patch.area_m2 * 1e6, patch.max_pressure_Pa * 1e-6,
                                patch.elements_in_contact);
            for (const PatchSolverResult& s : patch.solvers)
              rows += fmt::format(",{:.3f},{:.3f},{:.5f}", s.forces.F1_N, s.forces.F2_N, s.forces.M3_Nm);
            rows += fmt::format(",{:.3f},{:.3f},{:.3f},,\n", w.force_track_N[0], w.force_track_N[1], w.force_track_N[2]);
          }
        }
        return {rows, false};
      } catch (const Error& e) {
        // 17 patch columns, 3 per solver, 3 wheel forces left empty.
        return {fmt::format("{},failed,{},{}{},{}\n", k, inputs, std::string(17 + 3 * solver_count + 3, ','),
                            error_kind_name(e.kind()), csv_text(e.what())),
                true};
      }
    };
  };
}

namespace {

// The kind of a failed case's row (its error_kind column).
ErrorKind failed_kind(const std::string& row) {
  for (ErrorKind kind : {ErrorKind::invalid_input, ErrorKind::io, ErrorKind::no_contact, ErrorKind::several_patches,
                         ErrorKind::not_converged, ErrorKind::internal})
    if (row.find(fmt::format(",{},\"", error_kind_name(kind))) != std::string::npos) return kind;
  return ErrorKind::internal;
}

// sweep.csv, sweep.json and the figures from the complete set of cases (the CSV streamed: a
// large sweep's rows are in memory once, in `done`).
void write_outputs(output::OutputDirectory& dir, const std::string& metadata, const std::string& header,
                   const std::map<std::size_t, CaseResult>& done, std::ostream& log) {
  const std::string json_text = sweep_json(metadata, done);
  const auto write = [&](const char* name, const auto& write_text) {
    const std::filesystem::path path = dir.path(name);
    std::ofstream file(path, std::ios::binary);
    write_text(file);
    file.close();
    if (file.fail()) throw output::write_error(path, errno);
  };
  write("sweep.csv", [&](std::ostream& out) { write_sweep_csv(out, header, done); });
  write("sweep.json", [&](std::ostream& out) { out << json_text; });
  output::draw_figures("plot_sweep.py", dir.staging(), log);
}

void summarise_failures(const std::map<std::size_t, CaseResult>& done, SweepSummary& s) {
  for (const auto& [k, r] : done) {
    if (!r.failed) continue;
    if (s.failed++ == 0) {
      s.first_failed_case = k;
      s.first_failed_kind = failed_kind(r.text);
      const std::size_t quote = r.text.find(",\"");
      s.first_failed_message = quote == std::string::npos ? r.text : r.text.substr(quote + 2, r.text.size() - quote - 4);
    }
  }
}

}  // namespace

std::string sweep_journal_name(const Shard& shard) {
  return shard.whole() ? "sweep.journal" : fmt::format("sweep-shard-{}-of-{}.journal", shard.index, shard.count);
}

SweepSummary run_sweep(const SweepFile& sweep, const SweepRunOptions& options, std::ostream& log) {
  const WheelsetTrack track = wheelset_track(sweep.base);
  const Recipe recipe = make_recipe(sweep, track);
  const CaseWorkerFactory factory = sweep_worker_factory(sweep, track);
  SweepSummary summary;
  summary.cases = sweep.size();
  if (MpiWorld::rank() != 0) {  // an MPI rank other than 0: compute what rank 0 hands out
    run_cases_on_ranks({}, 1, factory, {});
    summary.worker_rank = true;
    return summary;
  }
  output::OutputDirectory dir(options.out, &log);
  const std::filesystem::path journal_path = dir.directory() / sweep_journal_name(options.shard);
  SweepJournalHeader header{RC_VERSION_STRING, recipe.hash, sweep.size(), options.shard, recipe.metadata, recipe.header};
  std::map<std::size_t, CaseResult> done;
  bool exists = false;
  std::uintmax_t valid_bytes = 0;
  if (options.restart) std::filesystem::remove(journal_path);
  if (std::filesystem::exists(journal_path)) {
    SweepJournal j = read_sweep_journal(journal_path, kResumeAdvice);
    if (j.header.recipe != recipe.hash || j.header.version != header.version || j.header.cases != header.cases ||
        j.header.shard.index != options.shard.index || j.header.shard.count != options.shard.count)
      throw Error(fmt::format(
          "{} holds {} completed cases of another sweep (railcontact {}, recipe {}, {} cases, shard {}/{}; this run: "
          "railcontact {}, recipe {}, {} cases, shard {}/{}): the sweep file, its set-up file, its profiles or railcontact "
          "changed. "
          "Rerun with --restart to discard them, or give another --out",
          journal_path.string(), j.done.size(), j.header.version, j.header.recipe, j.header.cases, j.header.shard.index,
          j.header.shard.count, header.version, header.recipe, header.cases, options.shard.index, options.shard.count));
    for (auto& [k, r] : j.done)
      if (options.shard.contains(k)) done.emplace(k, std::move(r));
    exists = true;
    valid_bytes = j.valid_bytes;
    if (j.dropped_tail) fmt::print(log, "note: dropped an incomplete record at the end of {} (an interrupted write)\n", journal_path.string());
  }
  std::vector<std::size_t> todo;
  for (std::size_t k = options.shard.index; k < summary.cases; k += options.shard.count) {
    ++summary.in_run;
    if (!done.contains(k)) todo.push_back(k);
  }
  summary.resumed = summary.in_run - todo.size();
  if (summary.resumed > 0)
    fmt::print(log, "sweep: resuming: {} of {} cases done in an earlier run ({}), {} to compute\n", summary.resumed,
               summary.in_run, journal_path.string(), todo.size());
  SweepJournalWriter writer(journal_path, header, exists, valid_bytes);
  ProgressLine progress(log, "cases", todo.size());
  std::size_t completed = 0;
  run_cases_on_ranks(todo, options.threads, factory, [&](std::size_t k, CaseResult&& r) {
    writer.append(k, r);
    done.emplace(k, std::move(r));
    progress.done(++completed);
  });
  writer.close();
  summary.computed = completed;
  summarise_failures(done, summary);
  if (!options.shard.whole()) {
    dir.commit();
    summary.written = journal_path;
    return summary;
  }
  write_outputs(dir, recipe.metadata, recipe.header, done, log);
  dir.commit();
  std::filesystem::remove(journal_path);
  summary.written = dir.directory() / "sweep.csv";
  return summary;
}

std::string sweep_json(const std::string& metadata, const std::map<std::size_t, CaseResult>& done) {
  nlohmann::json j = nlohmann::json::parse(metadata, nullptr, false);
  require(j.is_object(), "sweep: the metadata of the sweep is not a JSON object (a damaged journal?)");
  std::size_t failed = 0;
  for (const auto& entry : done) failed += entry.second.failed;
  j["failed_cases"] = failed;
  return j.dump(2) + "\n";
}

void write_sweep_csv(std::ostream& out, const std::string& header, const std::map<std::size_t, CaseResult>& done) {
  out << header;
  for (const auto& entry : done) out << entry.second.text;
}

SweepSummary merge_sweep_journals(const SweepJournalHeader& header, const std::map<std::size_t, CaseResult>& done,
                                  const std::filesystem::path& out, std::ostream& log) {
  sweep_json(header.metadata, done);  // a damaged journal's metadata refused before DIR is made
  output::OutputDirectory dir(out, &log);
  write_outputs(dir, header.metadata, header.header, done, log);
  dir.commit();
  SweepSummary summary;
  summary.cases = summary.in_run = header.cases;
  summary.resumed = done.size();
  summarise_failures(done, summary);
  summary.written = dir.directory() / "sweep.csv";
  return summary;
}

}  // namespace railcontact::study
