// `railcontact study …`: accuracy studies that reproduce the paper's tables and figures.
#include <fmt/core.h>

#include <iostream>
#include <string>

#include "cli/commands.hpp"
#include "railcontact/error.hpp"
#include "study/bound_study.hpp"
#include "study/coefficient_study.hpp"
#include "study/contact_surface_study.hpp"
#include "study/hertz_study.hpp"
#include "study/case_pool.hpp"
#include "study/mpi_cases.hpp"
#include "study/paper_study.hpp"
#include "study/patch_study.hpp"
#include "study/profile_pair_study.hpp"

namespace railcontact::cli {

namespace {

constexpr const char* kThreadsHelp =
    "threads for the independent cases (a whole number >= 1; default: all cores); the files do not depend on it";

// Default: every core; under mpirun one thread per rank.
int threads_of(const std::string& text) {
  if (!text.empty()) return study::parse_threads(text);
  return study::MpiWorld::several() ? 1 : study::available_cores();
}

// `study coefficients`: paper §3, Table 1, Fig 3 and Fig 4 against Kalker's table.
void add_coefficients_study(CLI::App* study, Action& action) {
  auto coefficients = std::make_shared<study::CoefficientStudyOptions>();
  auto out = std::make_shared<std::string>();
  CLI::App* cmd = study->add_subcommand("coefficients", "paper §3: Table 1, Fig 3 and Fig 4 against Kalker's table");
  cmd->add_option("--out", *out, "output directory")->required();
  cmd->add_option("--elements", coefficients->elements, "elements in contact for Table 1")->capture_default_str();
  cmd->add_option("--fine-elements", coefficients->fine_elements, "elements in contact for the refined Table 1")
      ->capture_default_str();
  cmd->add_flag("!--no-figures", coefficients->figures, "skip the figures (CSV and summary only)");
  auto coefficient_threads = std::make_shared<std::string>();
  cmd->add_option("--threads", *coefficient_threads, kThreadsHelp);
  cmd->callback([coefficients, out, coefficient_threads, &action] {
    action = [coefficients, out, coefficient_threads] {
      coefficients->threads = threads_of(*coefficient_threads);
      coefficients->output_directory = *out;
      study::run_coefficient_study(*coefficients, std::cerr);
      return 0;
    };
  });
}

// `study hertz`: creep curves on Hertzian ellipses with all four solvers.
void add_hertz_study(CLI::App* study, Action& action) {
  auto hertz = std::make_shared<study::HertzStudyOptions>();
  auto hertz_out = std::make_shared<std::string>();
  CLI::App* h = study->add_subcommand("hertz", "creep curves on ellipses a/b = 0.5, 1, 2 with all four solvers");
  h->add_option("--out", *hertz_out, "output directory")->required();
  h->add_option("--elements", hertz->elements, "elements in contact")->capture_default_str();
  h->add_option("--points", hertz->points, "creepage values per curve")->capture_default_str();
  h->add_flag("!--no-figures", hertz->figures, "skip the figures");
  h->callback([hertz, hertz_out, &action] {
    action = [hertz, hertz_out] {
      hertz->output_directory = *hertz_out;
      study::run_hertz_study(*hertz, std::cerr);
      return 0;
    };
  });
}

// `study bound`: nH-FastSim's error vs the traction-bound skew.
void add_bound_study(CLI::App* study, Action& action) {
  auto bound = std::make_shared<study::BoundStudyOptions>();
  auto bound_out = std::make_shared<std::string>();
  CLI::App* b = study->add_subcommand("bound", "nH-FastSim's error vs the traction-bound skew: ellipses and S1002/UIC60");
  b->add_option("--out", *bound_out, "output directory")->required();
  b->add_option("--elements", bound->elements, "elements in contact per patch")->capture_default_str();
  b->add_option("--y-step-m", bound->y_step_m, "step of the wheel-rail displacement (m, > 0)")->capture_default_str();
  auto bound_threads = std::make_shared<std::string>();
  b->add_option("--threads", *bound_threads, kThreadsHelp);
  b->callback([bound, bound_out, bound_threads, &action] {
    action = [bound, bound_out, bound_threads] {
      bound->threads = threads_of(*bound_threads);
      bound->output_directory = *bound_out;
      study::run_bound_study(*bound, std::cerr);
      return 0;
    };
  });
}

// `study patches`: wheel-rail normal contact over the wheelset displacement y.
void add_patch_study(CLI::App* study, Action& action) {
  auto patches = std::make_shared<study::PatchStudyOptions>();
  auto patches_out = std::make_shared<std::string>();
  auto wheel = std::make_shared<std::string>();
  auto rail = std::make_shared<std::string>();
  CLI::App* patch_cmd =
      study->add_subcommand("patches", "wheel-rail normal contact for y = -4.5 ... 4.5 mm (METHOD.md §9)");
  patch_cmd->add_option("--out", *patches_out, "output directory")->required();
  patch_cmd->add_option("--y-from-m", patches->y_from_m, "first wheelset displacement (m, + to the left)")
      ->capture_default_str();
  patch_cmd->add_option("--y-to-m", patches->y_to_m, "last wheelset displacement (m, + to the left)")
      ->capture_default_str();
  patch_cmd->add_option("--y-step-m", patches->y_step_m, "step of the displacement (m, > 0)")->capture_default_str();
  patch_cmd->add_option("--load-N", patches->vertical_load_N, "vertical wheel load Fz (N, > 0)")->capture_default_str();
  patch_cmd->add_option("--elements", patches->elements, "about this many elements in contact")->capture_default_str();
  patch_cmd->add_option("--wheel", *wheel, "wheel profile file (default: the shipped S1002)");
  patch_cmd->add_option("--rail", *rail, "rail profile file (default: the shipped UIC60 1:40)");
  patch_cmd->add_flag("!--no-figures", patches->figures, "skip the figures (CSV and summary only)");
  auto patch_threads = std::make_shared<std::string>();
  patch_cmd->add_option("--threads", *patch_threads, kThreadsHelp);
  patch_cmd->callback([patches, patches_out, wheel, rail, patch_threads, &action] {
    action = [patches, patches_out, wheel, rail, patch_threads] {
      patches->threads = threads_of(*patch_threads);
      patches->output_directory = *patches_out;
      if (!wheel->empty()) patches->wheel_profile = *wheel;
      if (!rail->empty()) patches->rail_profile = *rail;
      study::run_patch_study(*patches, std::cerr);
      return 0;
    };
  });
}

// `study paper`: the paper's §4 on S1002/UIC60, Fig 5-8.
void add_paper_study(CLI::App* study, Action& action) {
  auto paper = std::make_shared<study::PaperStudyOptions>();
  auto paper_out = std::make_shared<std::string>();
  CLI::App* pc = study->add_subcommand("paper", "paper §4 on S1002/UIC60: Fig 5 (error vs y), 6 (tractions), 7 (creep curves), 8 (time)");
  pc->add_option("--out", *paper_out, "output directory")->required();
  pc->add_option("--elements", paper->elements, "elements in contact per patch")->capture_default_str();
  pc->add_option("--y-step-m", paper->y_step_m, "step of y for Fig 5 (m, > 0)")->capture_default_str();
  pc->add_option("--samples", paper->timing_samples, "random cases per mesh size for Fig 8")->capture_default_str();
  pc->add_flag("!--no-figures", paper->figures, "skip the figures");
  auto paper_threads = std::make_shared<std::string>();
  pc->add_option("--threads", *paper_threads, kThreadsHelp);
  pc->callback([paper, paper_out, paper_threads, &action] {
    action = [paper, paper_out, paper_threads] {
      paper->threads = threads_of(*paper_threads);
      paper->output_directory = *paper_out;
      study::run_paper_study(*paper, std::cerr);
      return 0;
    };
  });
}

// `study profiles`: every wheel-rail set-up end to end (docs/VALIDATION.md "Other profile pairs").
void add_profile_pair_study(CLI::App* study, Action& action) {
  auto options = std::make_shared<study::ProfilePairStudyOptions>();
  auto out = std::make_shared<std::string>();
  auto setups = std::make_shared<std::vector<std::string>>();
  auto yaws = std::make_shared<std::vector<double>>();
  CLI::App* cmd = study->add_subcommand(
      "profiles", "every wheel-rail set-up end to end: conicity, the wheelset from y = 0 to flange climb at each yaw, "
                  "nH-FastSim against the exact solver, jumps along y");
  cmd->add_option("--out", *out, "output directory")->required();
  cmd->add_option("setups", *setups, "wheel-rail set-up files (default: every shipped set-up in data/wheel_rail)");
  cmd->add_option("--element-size-m", options->element_size_m, "element size (m)")->capture_default_str();
  cmd->add_option("--y-step-m", options->y_step_m, "step of the lateral displacement (m, > 0)")->capture_default_str();
  cmd->add_option("--yaw-rad", *yaws, "yaw angles (rad; default 0, 0.01, -0.01)");
  cmd->add_flag("!--no-table", options->table, "skip the wheelset table against the wheelset on the fly");
  auto surface = std::make_shared<std::string>();
  cmd->add_option("--contact-surface", *surface,
                  "the sweeps' and the tables' contact surface: planar (default), conformal or auto (docs/WHEELSET.md §4)");
  auto threads = std::make_shared<std::string>();
  cmd->add_option("--threads", *threads,
                  "threads for the wheelset tables' nodes (a whole number >= 1; default: all cores); the files do not "
                  "depend on it");
  cmd->add_flag("!--no-figures", options->figures, "skip the figures");
  cmd->callback([options, out, setups, yaws, threads, surface, &action] {
    action = [options, out, setups, yaws, threads, surface] {
      options->output_directory = *out;
      if (!surface->empty()) {
        try {
          options->contact_surface = parse_contact_surface(*surface);
        } catch (const Error& e) {
          throw Error(fmt::format("--contact-surface: {}", e.what()));
        }
      }
      options->threads = threads_of(*threads);
      for (const std::string& s : *setups) options->setups.emplace_back(s);
      if (!yaws->empty()) options->yaws_rad = *yaws;
      study::run_profile_pair_study(*options, std::cerr);
      return 0;
    };
  });
}

// `study surfaces`: the planar against the conformal contact surface, and the automatic one
// (docs/WHEELSET.md §4 "Choosing the surface").
void add_contact_surface_study(CLI::App* study, Action& action) {
  auto options = std::make_shared<study::ContactSurfaceStudyOptions>();
  auto out = std::make_shared<std::string>();
  auto setups = std::make_shared<std::vector<std::string>>();
  auto yaws = std::make_shared<std::vector<double>>();
  CLI::App* cmd = study->add_subcommand(
      "surfaces", "the planar against the conformal contact surface per patch along each set-up's sweep to flange "
                  "climb, and the automatic surface's blend swept in fine steps");
  cmd->add_option("--out", *out, "output directory")->required();
  cmd->add_option("setups", *setups, "wheel-rail set-up files (default: every shipped set-up in data/wheel_rail)");
  cmd->add_option("--element-size-m", options->element_size_m, "element size (m)")->capture_default_str();
  cmd->add_option("--y-step-m", options->y_step_m, "step of the lateral displacement (m, > 0)")->capture_default_str();
  cmd->add_option("--fine-y-step-m", options->fine_y_step_m, "step of the window where the automatic surface blends (m)")
      ->capture_default_str();
  cmd->add_option("--yaw-rad", *yaws, "yaw angles (rad; default 0, -0.01)");
  cmd->add_flag("!--no-figures", options->figures, "skip the figures");
  cmd->callback([options, out, setups, yaws, &action] {
    action = [options, out, setups, yaws] {
      options->output_directory = *out;
      for (const std::string& s : *setups) options->setups.emplace_back(s);
      if (!yaws->empty()) options->yaws_rad = *yaws;
      study::run_contact_surface_study(*options, std::cerr);
      return 0;
    };
  });
}

}  // namespace

void add_study_command(CLI::App& app, Action& action) {
  CLI::App* study = app.add_subcommand("study", "accuracy studies (CSV + figures + summary.md)");
  study->require_subcommand(1);
  add_coefficients_study(study, action);
  add_hertz_study(study, action);
  add_bound_study(study, action);
  add_patch_study(study, action);
  add_paper_study(study, action);
  add_profile_pair_study(study, action);
  add_contact_surface_study(study, action);
}

}  // namespace railcontact::cli
