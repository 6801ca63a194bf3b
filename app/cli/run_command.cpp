// `railcontact run [CASE.toml] [--json] [--out DIR] [--flextable FILE] [--slip-direction NAME]`: the main job.
#include <fmt/core.h>

#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "cli/commands.hpp"
#include "cli/note_on_success.hpp"
#include "case/case.hpp"
#include "case/case_output.hpp"
#include "case/case_run.hpp"
#include "railcontact/error.hpp"
#include "railcontact/flexibility_table.hpp"
#include "railcontact/tangential.hpp"

namespace railcontact::cli {
namespace {

struct RunArguments {
  std::string case_file;
  std::string out;
  std::string flextable;
  std::optional<std::string> slip_direction;  // --slip-direction (radial, flexibility-weighted, rigid-slip, elastic-slip): overrides the case file's
  bool json = false;
};

int run(const RunArguments& args) {
  const bool built_in = args.case_file.empty();
  Case input = built_in ? default_case() : read_case_file(args.case_file);
  if (args.slip_direction) {
    try {
      input.slip_direction = parse_slip_direction(*args.slip_direction);
    } catch (const Error& e) {
      throw Error(fmt::format("--slip-direction: {}", e.what()));
    }
  }
  CaseRunOptions options;
  if (!args.flextable.empty())
    options.flexibility_table = std::make_shared<const FlexibilityTable>(load_flexibility_table(args.flextable));
  const std::string recipe_note =
      options.flexibility_table ? older_nh_fastsim_recipe_note(options.flexibility_table->metadata().nh_fastsim_recipe)
                                : std::string();
  const NoteOnSuccess note(recipe_note.empty() ? recipe_note : args.flextable + ": " + recipe_note);
  // The built-in case always writes its outputs (default railcontact-out/). The directory is locked
  // (and its leftovers of an interrupted run removed) before the computation: a directory in use
  // by another run is refused at once.
  const std::string out = !args.out.empty() ? args.out : (built_in ? "railcontact-out" : "");
  std::optional<output::OutputDirectory> output;
  if (!out.empty()) output.emplace(out, &std::cerr);
  const CaseResult result = run_case(input, options, args.json ? nullptr : &std::cerr);
  if (args.json) {
    fmt::print("{}\n", case_result_json(result));
  } else {
    print_case_report(result, std::cout);
  }
  if (output) {
    write_case_outputs(result, *output, std::cerr);
    if (!args.json) fmt::print("\nWrote {}/ (result.json, tractions_*.csv, tractions.png)\n", out);
  }
  return 0;
}

}  // namespace

void add_run_command(CLI::App& app, Action& action) {
  auto args = std::make_shared<RunArguments>();
  CLI::App* cmd = app.add_subcommand("run", "run a case file (default: the built-in case) with its solvers");
  cmd->add_option("case", args->case_file, "TOML case file (docs/CASE_FILES.md)");
  cmd->add_flag("--json", args->json, "print one JSON object");
  cmd->add_option("--out", args->out, "write tractions (CSV), result.json and traction maps into this directory");
  cmd->add_option("--flextable", args->flextable,
                  "flexibility table (flextable build): nh-fastsim takes L1-L3 and the normalisation's f11, f22 from it "
                  "instead of K2 (wheel-rail cases)");
  cmd->add_option_function<std::string>(
      "--slip-direction", [args](const std::string& name) { args->slip_direction = name; },
      "nh-fastsim's slipping traction: radial (Eq 8, the default), flexibility-weighted, rigid-slip or "
      "elastic-slip (for flange patches; docs/FASTSIM.md \"The slip direction\"); overrides the case file's [solvers] slip_direction");
  cmd->callback([args, &action] { action = [args] { return run(*args); }; });
}

}  // namespace railcontact::cli
