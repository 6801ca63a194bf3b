// railcontact command-line tool: a thin layer over the library.
#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include "railcontact/error.hpp"

int main(int argc, char** argv) {
  CLI::App app{"railcontact: wheel-rail rolling contact (nH-FastSim and exact reference solvers)"};
  app.require_subcommand(1);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const railcontact::Error& e) {
    fmt::print(stderr, "railcontact: error: {}\n", e.what());
    return 1;
  }
  return 0;
}
