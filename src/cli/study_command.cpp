// `railcontact study …`: accuracy studies that reproduce the paper's tables and figures.
#include <iostream>
#include <string>

#include "cli/commands.hpp"
#include "study/coefficient_study.hpp"

namespace railcontact::cli {

void add_study_command(CLI::App& app, Action& action) {
  CLI::App* study = app.add_subcommand("study", "accuracy studies (CSV + figures + summary.md)");
  study->require_subcommand(1);

  auto coefficients = std::make_shared<study::CoefficientStudyOptions>();
  auto out = std::make_shared<std::string>();
  CLI::App* cmd = study->add_subcommand("coefficients", "paper §3: Table 1, Fig 3 and Fig 4 against Kalker's table");
  cmd->add_option("--out", *out, "output directory")->required();
  cmd->add_option("--elements", coefficients->elements, "elements in contact for Table 1")->capture_default_str();
  cmd->add_flag("!--figures", coefficients->figures, "skip the figures (CSV and summary only)");
  cmd->callback([coefficients, out, &action] {
    action = [coefficients, out] {
      coefficients->output_directory = *out;
      study::run_coefficient_study(*coefficients, std::cerr);
      return 0;
    };
  });
}

}  // namespace railcontact::cli
