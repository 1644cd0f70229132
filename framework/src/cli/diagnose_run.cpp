// `diagnose --run`: innovations of a filter run against its noise model (diagnose_run.hpp).

#include "diagnose_run.hpp"

#include <fmt/format.h>

#include <filesystem>

#include "stochnav/core/errors.hpp"
#include "stochnav/diagnose/innovation_report.hpp"
#include "stochnav/io/atomic_file.hpp"
#include "stochnav/report/gnuplot.hpp"

namespace stochnav::cli {
namespace {

namespace fs = std::filesystem;

// Window levels (mean u^2) over time, one line per component, one panel per aid, log scale,
// with the expected level 1 and each component's whole-run band.
void plot_levels(const InnovationAnalysis& analysis, const fs::path& output) {
  std::string script;
  const std::size_t panels = analysis.aids.size();
  script += fmt::format("set multiplot layout {},1\nset logscale y\nset grid\n", panels);
  script += "set key outside right\nset xlabel 't (s)'\nset ylabel 'window mean u^2'\n";
  for (std::size_t a = 0; a < panels; ++a) {
    const AidAnalysis& aid = analysis.aids[a];
    if (aid.windows.empty()) continue;
    std::vector<std::vector<double>> columns(aid.components.size() + 1);
    for (const auto& w : aid.windows) {
      columns[0].push_back(0.5 * (w.t0_s + w.t1_s));
      for (std::size_t i = 0; i < aid.components.size(); ++i) {
        columns[i + 1].push_back(std::max(w.level[i], 1e-12));
      }
    }
    std::vector<const std::vector<double>*> pointers;
    for (const auto& c : columns) pointers.push_back(&c);
    const std::string block = fmt::format("levels{}", a);
    script += gnuplot_datablock(block, pointers);
    script +=
        fmt::format("set title 'aid {} ({}): innovation level per {:.0f}-s window'\n",
                    aid.aid_index, aid.type, aid.windows.front().t1_s - aid.windows.front().t0_s);
    script += "plot 1 with lines dt 2 lw 2 lc rgb 'black' title 'expected (1)'";
    for (std::size_t i = 0; i < aid.components.size(); ++i) {
      script += fmt::format(", ${} using 1:{} with linespoints title '{}'", block, i + 2,
                            aid.components[i].name);
    }
    script += "\n";
  }
  script += "unset multiplot\n";
  render_gnuplot(script, output);
}

}  // namespace

void run_innovation_diagnosis(const std::string& run_dir, const std::string& out_dir,
                              const InnovationAnalysisOptions& options, const std::string& plots) {
  if (plots != "png" && plots != "svg" && plots != "none") {
    throw ConfigError("--plots '" + plots + "': use png, svg or none");
  }
  if (const auto problem = options.validate(); !problem.empty()) throw ConfigError(problem);
  const fs::path run(run_dir);
  const fs::path innovations = run / "innovations.csv";
  if (!fs::is_regular_file(innovations)) {
    throw InputError(innovations.string() +
                     ": not found; --run takes a folder written by `stochnav run --out`");
  }
  const fs::path out(out_dir);
  const std::string plot_name = plots == "none" ? "" : "innovation_levels." + plots;
  if (!plot_name.empty()) check_plot_request(out / plot_name);

  const InnovationAnalysis analysis = analyse_innovations(read_innovations(innovations), options);

  std::error_code error;
  fs::create_directories(out, error);
  if (error || !fs::is_directory(out)) {
    throw InputError(out.string() + ": cannot create the output folder (" + error.message() +
                     "); choose a writable --out");
  }
  // Render the plot first: if gnuplot fails, no report is written either.
  if (!plot_name.empty()) plot_levels(analysis, out / plot_name);
  write_file_atomically(out / "report.md",
                        innovation_report_markdown(analysis, run_dir, options, plot_name));
  write_file_atomically(out / "report.json",
                        innovation_report_json(analysis, run_dir, options).dump(2) + "\n");

  fmt::print("{}: {} ({} finding(s)); report in {}\n", run_dir,
             analysis.consistent ? "consistent" : "not consistent", analysis.findings.size(),
             (out / "report.md").string());
  for (const auto& f : analysis.findings) {
    fmt::print("  {} [{}]{}: {}\n", f.effect ? *f.effect : "overstated", f.aid_type,
               f.time_range_s ? fmt::format(" [{:.0f}, {:.0f}) s", f.time_range_s->first,
                                            f.time_range_s->second)
                              : std::string(),
               f.sensor);
  }
}

}  // namespace stochnav::cli
