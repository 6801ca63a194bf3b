// railcontact command-line tool: a thin layer over the library.
#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <exception>
#include <string>

#include "cli/commands.hpp"
#include "cli/renamed_options.hpp"
#include "railcontact/error.hpp"
#include "railcontact/version.h"
#include "study/mpi_cases.hpp"

namespace {
int run(int argc, char** argv);
}  // namespace

// Under mpirun with several ranks, an error on any rank ends them all (MPI_Abort) with its exit
// code: the others would otherwise wait for it forever.
int main(int argc, char** argv) {
  railcontact::study::MpiWorld mpi(argc, argv);
  if (const int ranks = railcontact::study::MpiWorld::ranks_without_mpi()) {
    fmt::print(stderr,
               "railcontact: error: started by mpirun with {} ranks, but this railcontact was built without MPI "
               "(RAILCONTACT_MPI=OFF, or libopenmpi-dev missing at configure time): run it without mpirun (--threads N), "
               "or rebuild it with MPI (docs/SCALING.md)\n",
               ranks);
    return railcontact::cli::exit_code(railcontact::ErrorKind::invalid_input);
  }
  return run(argc, argv);
}

namespace {
int run(int argc, char** argv) {
  CLI::App app{"railcontact: wheel-rail rolling contact (nH-FastSim and exact reference solvers)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("railcontact ") + RC_VERSION_STRING);
  app.failure_message([](const CLI::App*, const CLI::Error& e) { return std::string("railcontact: error: ") + e.what() + "\n"; });
  railcontact::cli::Action action;
  railcontact::cli::add_run_command(app, action);
  railcontact::cli::add_coefficients_command(app, action);
  railcontact::cli::add_patch_command(app, action);
  railcontact::cli::add_study_command(app, action);
  railcontact::cli::add_flextable_command(app, action);
  railcontact::cli::add_wheelset_command(app, action);
  railcontact::cli::add_wheelset_table_command(app, action);
  railcontact::cli::add_geometry_command(app, action);
  railcontact::cli::add_sweep_command(app, action);
  railcontact::cli::refuse_renamed_options(app);  // the options renamed to SI, refused with how to convert
  // Said once, in the top-level help (set after the commands, which would otherwise inherit it).
  app.footer("Units: the command line is SI throughout (m, rad, N, Pa, m/s, rad/s); the unit is in each option's name "
             "(--y-m, --yaw-rad, --load-N, --speed-m-per-s); JSON is SI. Human-readable output labels its units "
             "(it may show mm, mrad, kN).");
  if (argc > 1 && argv[1][0] != '-') {
    try {
      app.get_subcommand(argv[1]);
    } catch (const CLI::OptionNotFound&) {
      std::string names;
      for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
        names += (names.empty() ? "" : ", ") + sub->get_name();
      fmt::print(stderr, "railcontact: error: unknown command '{}' (commands: {})\n", argv[1], names);
      return 2;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);  // prints the message (or the help, code 0)
    return code == 0 ? 0 : railcontact::cli::exit_code(railcontact::ErrorKind::invalid_input);
  }
  try {
    return action ? action() : 0;
  } catch (const railcontact::Error& e) {
    fmt::print(stderr, "railcontact: error: {}\n", e.what());
    railcontact::study::MpiWorld::abort_all(railcontact::cli::exit_code(e.kind()));
    return railcontact::cli::exit_code(e.kind());
  } catch (const std::bad_alloc&) {
    fmt::print(stderr, "railcontact: error: out of memory (reduce the number of elements)\n");
    railcontact::study::MpiWorld::abort_all(railcontact::cli::kExitOutOfMemory);
    return railcontact::cli::kExitOutOfMemory;
  } catch (const std::exception& e) {
    fmt::print(stderr, "railcontact: error: internal error: {}\n", e.what());
  }
  railcontact::study::MpiWorld::abort_all(railcontact::cli::exit_code(railcontact::ErrorKind::internal));
  return railcontact::cli::exit_code(railcontact::ErrorKind::internal);
}
}  // namespace
