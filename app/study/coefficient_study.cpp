// The coefficient study (paper §3): Table 1, Fig 3 (collocation offset), Fig 4 (mesh size).
#include "study/coefficient_study.hpp"

#include <cerrno>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ostream.h>

#include "railcontact/tangential.hpp"
#include "railcontact/error.hpp"
#include "railcontact/kalker.hpp"
#include "study/case_pool.hpp"
#include "study/mpi_cases.hpp"
#include "output/figures.hpp"
#include "output/output_directory.hpp"

namespace railcontact::study {
namespace {


struct Configuration {
  std::string name;
  std::string description;
  EllipseCoefficientOptions options;
};

Configuration paper_configuration(int elements) {
  Configuration c{"paper", "the paper's set-up: n x n mesh, alpha = 0, c = sqrt(ab)", {}};
  c.options.target_elements = elements;
  c.options.layout = EllipseMeshLayout::equal_counts;
  c.options.adhesion = AdhesionOptions{};
  c.options.adhesion.tolerance = 1e-9;
  return c;
}

Configuration railcontact_configuration(int elements, bool c_from_area) {
  Configuration c{"railcontact",
                  c_from_area ? "rolling-resolved mesh, alpha = 0 (xi, eta) / 0.5 (phi), c from the discrete area"
                              : "rolling-resolved mesh, alpha = 0 (xi, eta) / 0.5 (phi), c = sqrt(ab)",
                  {}};
  c.options.target_elements = elements;
  c.options.layout = EllipseMeshLayout::rolling_resolved;
  c.options.adhesion.tolerance = 1e-9;
  c.options.c_from_discrete_area = c_from_area;
  return c;
}

std::array<double, 3> relative_errors(const CreepageCoefficients& computed, double C11, double C22, double C23) {
  return {computed.C11 / C11 - 1.0, computed.C22 / C22 - 1.0, computed.C23 / C23 - 1.0};
}

// Half a unit in the last of three significant digits, relative to the value.
double rounding_bound(double value) {
  const double unit = std::pow(10.0, std::floor(std::log10(value)) - 2.0);
  return 0.5 * unit / value;
}

struct TableStatistics {
  std::array<double, 3> max{}, mean{}, mean_beyond_rounding{};
  std::array<int, 3> within_rounding{};
  int entries = 0;
  double total_time_s = 0.0;
};

std::ofstream open_csv(const std::filesystem::path& path) {
  std::ofstream file(path);
  if (!file) throw output::write_error(path, errno);
  return file;
}

// Table 1's rows, each on its own (threads; under mpirun over the ranks), filed by row: the
// coefficients, elements and solve time of each (sent between ranks as text, an exact round trip).
// An MPI rank other than 0 computes what it is given and returns nothing.
std::vector<EllipseCoefficientResult> compute_table(const Configuration& configuration, int threads,
                                                    std::ostream& progress) {
  const auto rows = kalker_table_rows();
  std::vector<EllipseCoefficientResult> results(rows.size());
  std::vector<std::size_t> todo(rows.size());
  for (std::size_t k = 0; k < todo.size(); ++k) todo[k] = k;
  const CaseWorkerFactory factory = [&]() -> CaseWorker {
    return [&](std::size_t k) {
      const EllipseCoefficientResult r = ellipse_creepage_coefficients(rows[k].a_over_b, rows[k].nu, configuration.options);
      return CaseResult{fmt::format("{:.17g} {:.17g} {:.17g} {} {:.17g}", r.coefficients.C11, r.coefficients.C22,
                                    r.coefficients.C23, r.elements_in_contact, r.solve_time_s),
                        false};
    };
  };
  ProgressLine line(progress, "rows", rows.size());
  std::size_t done = 0;
  run_cases_on_ranks(todo, threads, factory, [&](std::size_t k, CaseResult&& text) {
    EllipseCoefficientResult& r = results[k];
    std::istringstream in(text.text);
    std::string c11, c22, c23, seconds;
    in >> c11 >> c22 >> c23 >> r.elements_in_contact >> seconds;
    r.coefficients.C11 = std::strtod(c11.c_str(), nullptr);
    r.coefficients.C22 = std::strtod(c22.c_str(), nullptr);
    r.coefficients.C23 = std::strtod(c23.c_str(), nullptr);
    r.solve_time_s = std::strtod(seconds.c_str(), nullptr);
    const auto e = relative_errors(r.coefficients, rows[k].c11, rows[k].c22, rows[k].c23);
    fmt::print(progress, "  [{:2}/{}] a/b = {:<7.4g} nu = {:.2f}: {} elements, errors {:+.2f}% {:+.2f}% {:+.2f}%\n",
               k + 1, rows.size(), rows[k].a_over_b, rows[k].nu, r.elements_in_contact, 100 * e[0], 100 * e[1],
               100 * e[2]);
    line.done(++done);
  });
  if (MpiWorld::rank() != 0) return {};
  return results;
}

TableStatistics write_table(const std::filesystem::path& path, const Configuration& configuration, int threads,
                            std::ostream& progress) {
  const std::vector<EllipseCoefficientResult> results = compute_table(configuration, threads, progress);
  std::ofstream csv = open_csv(path);
  csv << "a_over_b,nu,C11,C22,C23,table_C11,table_C22,table_C23,err_C11,err_C22,err_C23\n";
  const auto rows = kalker_table_rows();
  TableStatistics stats;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const auto& row = rows[k];
    const EllipseCoefficientResult& r = results[k];
    const auto e = relative_errors(r.coefficients, row.c11, row.c22, row.c23);
    const std::array<double, 3> table{row.c11, row.c22, row.c23};
    fmt::print(csv, "{:.6g},{:.2f},{:.6f},{:.6f},{:.6f},{},{},{},{:.6f},{:.6f},{:.6f}\n", row.a_over_b, row.nu,
               r.coefficients.C11, r.coefficients.C22, r.coefficients.C23, row.c11, row.c22, row.c23, e[0], e[1], e[2]);
    for (int j = 0; j < 3; ++j) {
      const double magnitude = std::fabs(e[j]);
      stats.max[j] = std::max(stats.max[j], magnitude);
      stats.mean[j] += magnitude;
      const double bound = rounding_bound(table[j]);
      stats.mean_beyond_rounding[j] += std::max(0.0, magnitude - bound);
      if (magnitude <= bound) ++stats.within_rounding[j];
    }
    ++stats.entries;
    stats.total_time_s += r.solve_time_s;
  }
  for (int j = 0; j < 3; ++j) {
    stats.mean[j] /= stats.entries;
    stats.mean_beyond_rounding[j] /= stats.entries;
  }
  return stats;
}

const std::array<double, 5> kStudyRatios{0.1, 0.5, 1.0, 2.0, 10.0};
constexpr double kStudyNu = 0.25;

const KalkerTableRow& table_row(double a_over_b, double nu) {
  for (const auto& row : kalker_table_rows())
    if (std::fabs(row.a_over_b / a_over_b - 1.0) < 1e-4 && std::fabs(row.nu - nu) < 1e-9) return row;
  throw Error(fmt::format("no Kalker table row for a/b = {}, nu = {}", a_over_b, nu));
}

// Fig 3: error against the collocation offset alpha, 80 x 80 mesh (the paper's).
void write_fig3(const std::filesystem::path& path, std::ostream& progress) {
  std::ofstream csv = open_csv(path);
  csv << "a_over_b,alpha,elements,err_C11,err_C22,err_C23\n";
  for (double ratio : kStudyRatios) {
    const auto& row = table_row(ratio, kStudyNu);
    for (int step = -9; step <= 10; ++step) {
      const double alpha = 0.1 * step;
      Configuration c = paper_configuration(0);
      c.options.target_elements = static_cast<int>(std::lround(M_PI / 4 * 80 * 80));
      c.options.adhesion.collocation_offset = alpha;
      c.options.adhesion.max_iterations = 1500;
      try {
        const EllipseCoefficientResult r = ellipse_creepage_coefficients(ratio, kStudyNu, c.options);
        const auto e = relative_errors(r.coefficients, row.c11, row.c22, row.c23);
        fmt::print(csv, "{:.6g},{:.1f},{},{:.6f},{:.6f},{:.6f}\n", ratio, alpha, r.elements_in_contact, e[0], e[1], e[2]);
      } catch (const Error& error) {  // alpha -> -1 decouples odd and even elements
        fmt::print(csv, "{:.6g},{:.1f},0,nan,nan,nan\n", ratio, alpha);
        fmt::print(progress, "  a/b = {} alpha = {:.1f}: {}\n", ratio, alpha, error.what());
      }
    }
    fmt::print(progress, "  fig 3: a/b = {} done\n", ratio);
  }
}

// Fig 4: error against the number of elements in contact, ~200 to ~11000, both configurations.
void write_fig4(const std::filesystem::path& path, int largest, std::ostream& progress) {
  std::ofstream csv = open_csv(path);
  csv << "config,a_over_b,n1,n2,elements,area_error,err_C11,err_C22,err_C23,solve_time_s\n";
  constexpr int kSteps = 12;
  for (double ratio : kStudyRatios) {
    const auto& row = table_row(ratio, kStudyNu);
    for (int step = 0; step < kSteps; ++step) {
      const int target = static_cast<int>(std::lround(200.0 * std::pow(largest / 200.0, step / (kSteps - 1.0))));
      for (const Configuration& c : {paper_configuration(target), railcontact_configuration(target, true)}) {
        const EllipseCoefficientResult r = ellipse_creepage_coefficients(ratio, kStudyNu, c.options);
        const auto e = relative_errors(r.coefficients, row.c11, row.c22, row.c23);
        fmt::print(csv, "{},{:.6g},{},{},{},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f}\n", c.name, ratio, r.n1, r.n2,
                   r.elements_in_contact, r.area_error, e[0], e[1], e[2], r.solve_time_s);
      }
    }
    fmt::print(progress, "  fig 4: a/b = {} done\n", ratio);
  }
}

void write_statistics(std::ostream& md, const std::string& title, const std::string& file, const Configuration& c,
                      const TableStatistics& s) {
  fmt::print(md, "### {} (`{}`)\n\n{}; about {} elements in contact.\n\n", title, file, c.description,
             c.options.target_elements);
  md << "| | C11 | C22 | C23 |\n|---|---|---|---|\n";
  fmt::print(md, "| max error | {:.2f}% | {:.2f}% | {:.2f}% |\n", 100 * s.max[0], 100 * s.max[1], 100 * s.max[2]);
  fmt::print(md, "| mean error | {:.2f}% | {:.2f}% | {:.2f}% |\n", 100 * s.mean[0], 100 * s.mean[1], 100 * s.mean[2]);
  fmt::print(md, "| entries within the table's rounding | {}/{} | {}/{} | {}/{} |\n", s.within_rounding[0], s.entries,
             s.within_rounding[1], s.entries, s.within_rounding[2], s.entries);
  fmt::print(md, "| mean error beyond the rounding | {:.2f}% | {:.2f}% | {:.2f}% |\n\n", 100 * s.mean_beyond_rounding[0],
             100 * s.mean_beyond_rounding[1], 100 * s.mean_beyond_rounding[2]);
  const double overall_max = std::max({s.max[0], s.max[1], s.max[2]});
  const double overall_mean = (s.mean[0] + s.mean[1] + s.mean[2]) / 3.0;
  fmt::print(md, "Over all {} numbers: max {:.2f}%, mean {:.2f}%. K2 time for the 57 patches: {:.2f} s.\n\n",
             3 * s.entries, 100 * overall_max, 100 * overall_mean, s.total_time_s);
}

}  // namespace

void run_coefficient_study(const CoefficientStudyOptions& options, std::ostream& progress) {
  require(options.elements >= 50 && options.elements <= 200000, [&] {
    return fmt::format("study coefficients: --elements must lie in [50, 200000] (got {})", options.elements);
  });
  const Configuration ours = railcontact_configuration(options.elements, false);
  const Configuration paper = paper_configuration(options.elements);
  const Configuration fine = railcontact_configuration(options.fine_elements, true);
  if (MpiWorld::rank() != 0) {  // under mpirun: the rows of the three tables rank 0 hands out, nothing else
    for (const Configuration* c : {&ours, &paper, &fine}) compute_table(*c, options.threads, progress);
    return;
  }
  output::OutputDirectory output(options.output_directory, &progress);  // locked, staged (docs/RELIABILITY.md "Outputs")
  const std::filesystem::path& dir = output.staging();
  const auto start = std::chrono::steady_clock::now();

  fmt::print(progress, "Table 1, {} ({} elements):\n", ours.description, options.elements);
  const TableStatistics s_ours = write_table(dir / "table1.csv", ours, options.threads, progress);
  fmt::print(progress, "Table 1, {} ({} elements):\n", paper.description, options.elements);
  const TableStatistics s_paper = write_table(dir / "table1_paper.csv", paper, options.threads, progress);
  fmt::print(progress, "Table 1, {} ({} elements):\n", fine.description, options.fine_elements);
  const TableStatistics s_fine = write_table(dir / "table1_fine.csv", fine, options.threads, progress);
  fmt::print(progress, "Fig 3 (collocation offset):\n");
  write_fig3(dir / "fig3.csv", progress);
  fmt::print(progress, "Fig 4 (mesh size):\n");
  write_fig4(dir / "fig4.csv", options.fine_elements, progress);

  std::ofstream md(dir / "summary.md");
  if (!md) throw output::write_error(dir / "summary.md", errno);
  md << "# Creepage coefficients from the full-adhesion steady-state solution (paper §3)\n\n"
        "Relative errors of C11, C22, C23 from K2 (Eq 18) against Kalker's table (57 entries: 19 a/b x 3 nu; "
        "the nu = 0.5 rows solved at nu = 0.5 - 1e-9). Kalker's table has three significant digits: the "
        "rounding alone allows up to 0.05/C relative (0.1% to 0.4%).\n\n";
  write_statistics(md, "Table 1, railcontact defaults", "table1.csv", ours, s_ours);
  write_statistics(md, "Table 1, the paper's configuration", "table1_paper.csv", paper, s_paper);
  write_statistics(md, "Table 1, refined", "table1_fine.csv", fine, s_fine);
  md << "Figures: `fig3.png` (error against the collocation offset, 80 x 80 mesh, nu = 0.25), `fig4.png` "
        "(error against the number of elements in contact, nu = 0.25, both configurations; the area error of the "
        "staircase patch is in `fig4.csv`), `table1.png` (errors of the three tables).\n";
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  fmt::print(md, "\nStudy run time: {:.1f} s.\n", total);
  md.close();
  if (!md) throw output::write_error(dir / "summary.md", errno);
  if (options.figures) output::draw_figures("plot_coefficient_study.py", dir, progress);
  output.commit();
  fmt::print(progress, "Wrote {}\n", options.output_directory.string());
}

}  // namespace railcontact::study
