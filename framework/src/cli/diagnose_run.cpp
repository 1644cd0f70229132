// `diagnose --run`: innovations of a filter run against its noise model (diagnose_run.hpp).

#include "diagnose_run.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <filesystem>

#include "stochnav/core/errors.hpp"
#include "stochnav/diagnose/innovation_aux.hpp"
#include "stochnav/diagnose/innovation_report.hpp"
#include "stochnav/io/record.hpp"
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
      script += fmt::format(", ${} using 1:{} with linespoints title {}", block, i + 2,
                            gnuplot_string(aid.components[i].name));
    }
    script += "\n";
  }
  script += "unset multiplot\n";
  render_gnuplot(script, output);
}

}  // namespace

void run_innovation_diagnosis(const std::string& run_dir, const std::string& out_dir,
                              const InnovationAnalysisOptions& options, const std::string& plots,
                              const std::vector<std::string>& aux_columns,
                              const std::string& aux_file) {
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

  const std::vector<AidInnovations> samples = read_innovations(innovations);
  const InnovationAnalysis analysis = analyse_innovations(samples, options);
  std::vector<InnovationAuxFinding> aux_findings;
  if (!aux_columns.empty()) {
    const fs::path channel_file = aux_file.empty() ? run / "aids.csv" : fs::path(aux_file);
    if (!fs::is_regular_file(channel_file)) {
      throw InputError(channel_file.string() +
                       ": not found; --aux reads its columns from RUN_DIR/aids.csv or --aux-file");
    }
    std::vector<TimedChannel> channels;
    for (const std::string& column : aux_columns) {
      ReadOptions read;
      read.path = channel_file.string();
      read.column = column;
      const Record record = read_record(read);
      channels.push_back({column, record.start_time_s, record.rate_hz, record.values});
    }
    aux_findings = innovation_aux_findings(samples, analysis, channels, options.alpha);
  }

  OutputFolder out_folder(out);
  // Render the plot first: if gnuplot fails, no report is written either.
  if (!plot_name.empty()) plot_levels(analysis, out / plot_name);
  std::string markdown = innovation_report_markdown(analysis, run_dir, options, plot_name);
  nlohmann::json report = innovation_report_json(analysis, run_dir, options);
  if (!aux_columns.empty()) {
    markdown += "\n## Drift with auxiliary channels\n\n";
    if (aux_findings.empty()) {
      markdown += fmt::format("No innovation component drifts with {} (alpha {}).\n",
                              fmt::join(aux_columns, ", "), options.alpha);
    }
    nlohmann::json drift = nlohmann::json::array();
    for (const auto& f : aux_findings) {
      markdown += "- " + f.evidence + "\n";
      drift.push_back({{"effect", "aux_sensitivity"}, {"aid_index", f.aid_index},
                       {"aid_type", f.aid_type}, {"component", f.component},
                       {"column", f.column}, {"slope", f.slope},
                       {"slope_sigma", f.slope_sigma}, {"t", f.t_statistic},
                       {"p_value", f.p_value}, {"t_with_time", f.t_with_time},
                       {"evidence", f.evidence}});
    }
    report["aux_drift"] = std::move(drift);
  }
  write_file_atomically(out / "report.md", markdown);
  write_file_atomically(out / "report.json", report.dump(2) + "\n");
  out_folder.keep();

  fmt::print("{}: {} ({} finding(s)); report in {}\n", run_dir,
             analysis.consistent ? "consistent" : "not consistent", analysis.findings.size(),
             (out / "report.md").string());
  for (const auto& f : aux_findings) {
    fmt::print("  aux_sensitivity [{}] {} drifts with {} (t = {:.1f})\n", f.aid_type, f.component,
               f.column, f.t_statistic);
  }
  for (const auto& f : analysis.findings) {
    fmt::print("  {} [{}]{}: {}\n", f.effect ? *f.effect : "overstated", f.aid_type,
               f.time_range_s ? fmt::format(" [{:.0f}, {:.0f}) s", f.time_range_s->first,
                                            f.time_range_s->second)
                              : std::string(),
               f.sensor);
  }
}

}  // namespace stochnav::cli
