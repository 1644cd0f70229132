// stochnav davar: the dynamic Allan deviation, streamed from the file window by window.

#include <fmt/format.h>

#include <cerrno>
#include <fstream>
#include <memory>
#include <sstream>

#include "command_support.hpp"
#include "commands.hpp"
#include "davar_plot.hpp"
#include "standard_output.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/io/atomic_file.hpp"
#include "stochnav/io/sample_reader.hpp"
#include "stochnav/report/gnuplot.hpp"
#include "stochnav/stats/davar.hpp"

namespace stochnav::cli {
namespace {

struct DavarArguments {
  InputArguments input;
  std::size_t window = 0;
  std::size_t step = 0;
  bool causal = false;
  std::string format = "table";
  std::string plot;
  std::string output;
};

/// Writes rows as they complete. JSON puts "tau" first and "t" last, so only the analysis
/// times (one number per window) are held until the end.
class DavarWriter {
 public:
  DavarWriter(OutputFormat format, std::ostream& out) : format_(format), out_(out) {
    out_.precision(10);
  }

  void begin(const std::vector<double>& tau_s, const std::vector<std::size_t>& terms) {
    switch (format_) {
      case OutputFormat::kJson:
        out_ << "{\"tau\": [" << join(tau_s) << "],\n \"adev\": [";
        break;
      case OutputFormat::kCsv:
        out_ << "t";
        for (double tau : tau_s) out_ << ",adev_tau_" << tau;
        out_ << '\n';
        break;
      case OutputFormat::kTable:
        out_ << fmt::format("# dynamic overlapping Allan deviation; terms per window:");
        for (auto n : terms) out_ << ' ' << n;
        out_ << "\n#" << fmt::format("{:>13}", "t_s \\ tau_s");
        for (double tau : tau_s) out_ << fmt::format(" {:>11.4e}", tau);
        out_ << '\n';
        break;
    }
  }

  void row(const DavarRow& row) {
    times_.push_back(row.time_s);
    switch (format_) {
      case OutputFormat::kJson:
        out_ << (times_.size() == 1 ? "\n  [" : ",\n  [") << join(row.deviation) << ']';
        break;
      case OutputFormat::kCsv:
        out_ << row.time_s;
        for (double d : row.deviation) out_ << ',' << d;
        out_ << '\n';
        break;
      case OutputFormat::kTable:
        out_ << fmt::format("{:>14.6g}", row.time_s);
        for (double d : row.deviation) out_ << fmt::format(" {:>11.4e}", d);
        out_ << '\n';
        break;
    }
  }

  void end() {
    if (format_ == OutputFormat::kJson) out_ << "],\n \"t\": [" << join(times_) << "]}\n";
  }

 private:
  std::string join(const std::vector<double>& values) const {
    std::ostringstream text;
    text.precision(17);
    for (std::size_t i = 0; i < values.size(); ++i) text << (i ? ", " : "") << values[i];
    return text.str();
  }

  OutputFormat format_;
  std::ostream& out_;
  std::vector<double> times_;
};

void run_davar(const DavarArguments& arguments) {
  const OutputFormat format = parse_format(arguments.format);
  if (!arguments.plot.empty()) check_plot_request(arguments.plot);
  DavarOptions options{.window = arguments.window, .step = arguments.step,
                       .causal = arguments.causal, .m_values = {}};
  if (const auto problem = options.validate(0); !problem.empty()) throw ConfigError(problem);

  ReadOptions read_options = arguments.input.to_read_options();
  // The windows are computed as the blocks are read: the bytes read measure the whole run.
  const auto progress = reading_progress("davar", read_options);
  SampleReader reader(read_options);
  std::vector<double> block;
  // Blocks of 2^18 samples (2 MB): few hand-overs to the DAVAR threads, memory still flat.
  constexpr std::size_t kBlock = 1 << 18;
  reader.read_block(block, kBlock);

  // Output goes to a pending file (or a buffer for standard output): nothing half-written.
  const bool to_stdout = arguments.output.empty() || arguments.output == "-";
  std::unique_ptr<PendingFile> pending;
  std::ofstream file;
  std::ostringstream buffer;
  if (!to_stdout) {
    pending = std::make_unique<PendingFile>(arguments.output);
    file = pending->open_stream();
  }
  std::ostream& out = to_stdout ? static_cast<std::ostream&>(buffer) : file;
  DavarWriter writer(format, out);
  DavarPlotData plot_data;
  const bool plotting = !arguments.plot.empty();
  DavarAccumulator davar(options, read_options.kind, reader.rate_hz(), reader.start_time_s(),
                         [&](const DavarRow& row) {
                           writer.row(row);
                           if (plotting) plot_data.add_row(row);
                         });
  std::vector<double> tau_s;
  for (std::size_t m : davar.m_values()) tau_s.push_back(static_cast<double>(m) / reader.rate_hz());
  writer.begin(tau_s, davar.term_counts());
  do {
    davar.push(block);
    block.clear();
  } while (reader.read_block(block, kBlock) > 0);
  if (reader.samples_read() < options.window) {
    throw ConfigError(read_options.path + ": " + options.validate(reader.samples_read()));
  }
  writer.end();
  progress->finish();
  if (plotting) {
    plot_data.tau_s = tau_s;
    plot_davar(plot_data, read_options.path + " [" + reader.column_name() + "]",
               unit_name(read_options.unit), arguments.plot);
  }
  if (to_stdout) {
    write_standard_output(buffer.str());
  } else {
    file.close();
    if (!file) throw_write_error(arguments.output, errno);
    pending->commit();
  }
}

}  // namespace

void add_davar_command(CLI::App& app) {
  auto arguments = std::make_shared<DavarArguments>();
  CLI::App* command = app.add_subcommand("davar", "Dynamic Allan deviation over sliding windows");
  add_input_options(*command, arguments->input);
  command->add_option("--window", arguments->window, "Samples per window")
      ->required()
      ->check(positive_count());
  command->add_option("--step", arguments->step, "Samples between window starts")
      ->required()
      ->check(positive_count());
  command->add_flag("--causal", arguments->causal,
                    "Time each window at its end (trailing windows) instead of its centre");
  add_format_option(*command, arguments->format);
  command->add_option("--plot", arguments->plot, "Draw the DAVAR heat map to FILE.png or FILE.svg");
  command->add_option("--output", arguments->output, "Write to FILE instead of standard output");
  command->callback([arguments] { run_davar(*arguments); });
}

}  // namespace stochnav::cli
