// `railcontact study …`: accuracy studies that reproduce the paper's tables and figures.
#include <iostream>
#include <string>

#include "cli/commands.hpp"
#include "study/coefficient_study.hpp"
#include "study/hertz_study.hpp"

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

  auto hertz = std::make_shared<study::HertzStudyOptions>();
  auto hertz_out = std::make_shared<std::string>();
  CLI::App* h = study->add_subcommand("hertz", "creep curves on ellipses a/b = 0.5, 1, 2 with all four solvers");
  h->add_option("--out", *hertz_out, "output directory")->required();
  h->add_option("--elements", hertz->elements, "elements in contact")->capture_default_str();
  h->add_option("--points", hertz->points, "creepage values per curve")->capture_default_str();
  h->add_flag("!--figures", hertz->figures, "skip the figures");
  h->callback([hertz, hertz_out, &action] {
    action = [hertz, hertz_out] {
      hertz->output_directory = *hertz_out;
      study::run_hertz_study(*hertz, std::cerr);
      return 0;
    };
  });
}

}  // namespace railcontact::cli
