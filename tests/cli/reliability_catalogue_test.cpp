// The catalogue of issues #17 (a fuzzing and sanitizer pass over every subcommand) and #26 (the
// tool as a trusted Unix tool: write errors, special files, inputs checked whole) as tables:
// each defect found, run through the command-line tool. Every bad input gives exit code 2 and
// one printable line saying what and where, names no internal function, and leaves no output,
// no temporary file and no folder behind; the inputs that were mishandled although valid (a
// UTF-8 byte-order mark, a subnormal number) now work.

#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "json_file.hpp"
#include "run_cli.hpp"
#include "temp_dir.hpp"
#include "tiny_comparison.hpp"

namespace stochnav {
namespace {

using testing::CliResult;
using testing::TempDir;
namespace fs = std::filesystem;

struct CatalogueCase {
  std::string name;
  std::string arguments;  ///< '@' stands for the fixture's folder
  int exit_code = 2;
  std::string fragment;                  ///< in the message (exit 2) or on standard output (exit 0)
  std::vector<std::string> absent = {};  ///< paths under '@' that must not exist afterwards
  std::string shell_prefix = {};         ///< sh commands before the tool (ulimit)
};
void PrintTo(const CatalogueCase& c, std::ostream* os) { *os << c.name; }

std::string replace_at(std::string text, const std::string& dir) {
  for (std::size_t at = text.find('@'); at != std::string::npos; at = text.find('@', at)) {
    text.replace(at, 1, dir);
    at += dir.size();
  }
  return text;
}

// run_cli with shell commands first (sh -c 'PREFIX; exec stochnav ARGS').
CliResult run_in_shell(const std::string& prefix, const std::string& arguments,
                       const std::string& scratch) {
  if (prefix.empty()) return testing::run_cli(arguments, scratch);
  const std::string err_path = scratch + "/stderr.txt";
  const std::string script = prefix + "; exec '" + STOCHNAV_CLI_PATH + "' " + arguments;
  std::string quoted;
  for (char c : script) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  const std::string command = "sh -c '" + quoted + "' 2> '" + err_path + "'";
  CliResult result;
  std::FILE* pipe = ::popen(command.c_str(), "r");
  std::array<char, 4096> chunk{};
  while (std::fgets(chunk.data(), chunk.size(), pipe) != nullptr) result.out += chunk.data();
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream err(err_path);
  result.err.assign(std::istreambuf_iterator<char>(err), {});
  fs::remove(err_path);
  return result;
}

using testing::read_json;

std::string csv(int rows) {
  std::string text = "t,x\n";
  for (int i = 0; i < rows; ++i)
    text += std::to_string(i) + "," + std::to_string((i * 7) % 5) + "\n";
  return text;
}

// Writes an IMU file like `source` with each data row passed through `edit` (row index, cells).
template <typename Edit>
void edited_imu(const fs::path& source, const fs::path& folder, Edit edit) {
  fs::create_directories(folder);
  for (const char* name : {"aids.csv", "truth.csv", "scenario.json"}) {
    fs::copy_file(source.parent_path() / name, folder / name);
  }
  std::ifstream in(source);
  std::ofstream out(folder / "imu.csv");
  std::string line;
  std::getline(in, line);
  out << line << '\n';
  for (int row = 0; std::getline(in, line); ++row) {
    std::vector<std::string> cells;
    for (std::size_t start = 0;;) {
      const std::size_t comma = line.find(',', start);
      cells.push_back(line.substr(start, comma - start));
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
    if (!edit(row, cells)) continue;
    for (std::size_t i = 0; i < cells.size(); ++i) out << (i ? "," : "") << cells[i];
    out << '\n';
  }
}

// Copies the recording folder `source` to `folder` with the data lines (after the header) of
// `file` passed through `edit`.
template <typename Edit>
void edited_lines(const fs::path& source, const std::string& file, const fs::path& folder,
                  Edit edit) {
  fs::create_directories(folder);
  for (const char* name : {"imu.csv", "aids.csv", "truth.csv", "scenario.json"}) {
    if (name != file) fs::copy_file(source / name, folder / name);
  }
  std::ifstream in(source / file);
  std::string header;
  std::getline(in, header);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  edit(lines);
  std::ofstream out(folder / file);
  out << header << '\n';
  for (const std::string& line : lines) out << line << '\n';
}

// `text` (a JSON object as nlohmann dumps it) with `"key":value` written a second time after
// the first occurrence of `"key":value`.
std::string with_key_twice(std::string text, const std::string& key_value) {
  const std::size_t at = text.find(key_value);
  if (at == std::string::npos) return "key not found: " + key_value;
  return text.insert(at + key_value.size(), "," + key_value);
}

class Catalogue : public ::testing::TestWithParam<CatalogueCase> {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir();
    const TempDir& d = *dir_;
    d.write("good.csv", csv(200));
    d.write("long.csv", csv(2000));
    std::string alternating = "t,x\n";
    for (int i = 0; i < 200; ++i)
      alternating += std::to_string(i) + (i % 2 ? ",1e308\n" : ",-1e308\n");
    d.write("alternating.csv", alternating);
    d.write("cr_only.csv", "t,x\r0,1\r1,2\r2,3\r3,4\r");
    d.write("control.csv", "t,x\n0,1\n1,2\x1b[31mred\x07\n2,3\n");
    d.write("bom.csv", "\xEF\xBB\xBF" + csv(200));
    d.write("crlf.csv", "t,x\r\n0,1\r\n1,3\r\n2,2\r\n3,5\r\n4,1\r\n5,0\r\n6,4\r\n7,2\r\n");
    const std::string model = R"({"units": "deg/h", "rate_hz": 10, "terms": [
        {"type": "angle_random_walk", "N": 0.1}]})";
    d.write("model.json", model);
    d.write("model_1e400.json", R"({"units": "deg/h", "rate_hz": 10, "terms": [
        {"type": "angle_random_walk", "N": 1e400}]})");
    d.write("model_huge.json", R"({"units": "deg/h", "rate_hz": 10, "terms": [
        {"type": "angle_random_walk", "N": 1e307}]})");
    d.write("model_subnormal.json", R"({"units": "deg/h", "rate_hz": 10, "terms": [
        {"type": "angle_random_walk", "N": 1e-320}]})");
    fs::create_directories(d.path() / "folder.json");

    // A still vibration table, 30 s at 100 Hz, and a run config on it.
    nlohmann::json scenario = read_json(std::string(STOCHNAV_SOURCE_DIR) +
                                        "/configs/scenarios/paper_fixed_frequency.json");
    scenario["vibration_table"]["phases"] = {
        {{"name", "static"}, {"duration_s", 30}, {"motion", "static"}}};
    d.write("scenario.json", scenario.dump());
    nlohmann::json subnormal_scenario = scenario;
    subnormal_scenario["sensors"]["gyro"]["noise"]["terms"] = {
        {{"type", "angle_random_walk"}, {"N", 1e-320}}};
    d.write("scenario_subnormal.json", subnormal_scenario.dump());
    nlohmann::json long_scenario = scenario;
    long_scenario["vibration_table"]["phases"][0]["duration_s"] = 1e12;
    d.write("scenario_1e12.json", long_scenario.dump());
    std::string text = scenario.dump();
    d.write("scenario_1e400.json", text.replace(text.find("\"seed\":") + 7, 0, "1e400, \"x\":"));
    const CliResult simulated = testing::run_cli(
        "simulate scenario '" + d.file("scenario.json") + "' --out '" + d.file("table") + "'",
        d.path().string());
    if (simulated.exit_code != 0) setup_error_ = simulated.err;

    const fs::path imu = d.path() / "table" / "imu.csv";
    edited_imu(imu, d.path() / "gap", [](int row, auto&) { return row < 1000 || row >= 1010; });
    edited_imu(imu, d.path() / "rate_change", [](int row, std::vector<std::string>& cells) {
      if (row >= 1500) cells[0] = std::to_string(15.0 + (row - 1499) * 0.005);
      return true;
    });
    edited_imu(imu, d.path() / "spike", [](int row, std::vector<std::string>& cells) {
      if (row == 700) cells[1] = "1e150";
      return true;
    });
    const nlohmann::json run = {
        {"data", {{"scenario", "table"}}},
        {"noise",
         {{"gyro", {{"plugin", "white"}, {"params", {{"N", 0.005}}}}},
          {"accel", {{"plugin", "white"}, {"params", {{"N", 0.03}}}}}}},
        {"aids",
         {{{"plugin", "static_position"},
           {"params", {{"sigma_position_m", 0.01}, {"sigma_velocity_mps", 0.3}}}}}},
        {"filter", stochnav::testing::vibration_table_filter()}};
    d.write("run.json", run.dump());
    nlohmann::json broken = run;
    broken["noise"]["gyro"]["plugin"] = "mymodel";
    d.write("run_broken_plugin.json", broken.dump());
    d.write("stochnav_noise_mymodel.so", "not an ELF file");
    text = run.dump();
    d.write("run_1e400.json", text.replace(text.find("0.005"), 5, "1e400"));
    const nlohmann::json experiment = {
        {"data", {{"scenario_config", "scenario.json"}, {"seeds", 1}}},
        {"baseline", "classic"},
        {"aids", run["aids"]},
        {"filter", run["filter"]},
        {"variants", {{{"name", "classic"}, {"noise", run["noise"]}}}}};
    d.write("experiment.json", experiment.dump());
    nlohmann::json many_seeds = experiment;
    many_seeds["data"]["seeds"] = 1000000;
    d.write("experiment_1e6_seeds.json", many_seeds.dump());
    text = experiment.dump();
    d.write("experiment_1e400.json", text.replace(text.find("0.005"), 5, "1e400"));

    // Issue #26.
    edited_lines(d.path() / "table", "truth.csv", d.path() / "truth_swapped",
                 [](std::vector<std::string>& lines) { std::swap(lines[150], lines[151]); });
    edited_lines(d.path() / "table", "truth.csv", d.path() / "truth_duplicated",
                 [](std::vector<std::string>& lines) {
                   lines.insert(lines.begin() + 200, lines[200]);
                 });
    d.write("model_duplicate.json", R"({"units": "deg/h", "rate_hz": 10, "terms": [
        {"type": "angle_random_walk", "N": 0.1, "N": 0.2}]})");
    d.write("run_duplicate.json",
            with_key_twice(run.dump(), "\"plugin\":\"static_position\""));
    d.write("experiment_duplicate.json",
            with_key_twice(experiment.dump(), "\"baseline\":\"classic\""));
    d.write("scenario_duplicate.json", with_key_twice(scenario.dump(), "\"duration_s\":30"));
    // gzip records: whole, cut short, a byte of the data changed, no gzip header.
    d.write("record.txt", [] {
      std::string record;
      for (int i = 0; i < 2000; ++i) record += std::to_string((i * 37) % 101 - 50) + "\n";
      return record;
    }());
    const std::string gzip = "gzip -n -c '" + d.file("record.txt") + "' > '" +
                             d.file("record.txt.gz") + "'";
    if (std::system(gzip.c_str()) != 0) setup_error_ = "gzip failed";
    std::ifstream compressed(d.file("record.txt.gz"), std::ios::binary);
    const std::string bytes{std::istreambuf_iterator<char>(compressed), {}};
    d.write("truncated.txt.gz", bytes.substr(0, bytes.size() / 3));
    std::string corrupt = bytes;
    corrupt[corrupt.size() - 6] = static_cast<char>(corrupt[corrupt.size() - 6] ^ 0x55);
    d.write("corrupt.txt.gz", corrupt);
    d.write("headerless.txt.gz", bytes.substr(3));
    // Fits that fail, models flagged failed, absurd rates and magnitudes.
    d.write("sinusoid.csv", [] {
      // A noiseless sinusoid, A = 1 deg/h, f = 0.05 Hz, 2000 s at 10 Hz.
      std::string record = "t,x\n";
      for (int i = 0; i < 20000; ++i) {
        const double t = i / 10.0;
        char line[64];
        std::snprintf(line, sizeof line, "%.1f,%.12g\n", t, std::sin(2.0 * std::numbers::pi * 0.05 * t));
        record += line;
      }
      return record;
    }());
    d.write("failed_fit.json", R"({"units": "deg/h", "rate_hz": 10, "terms": [
        {"type": "angle_random_walk", "N": 0.1, "N_sigma": 0.01}],
        "diagnostics": {"failed": true, "failure": "chi-square 2671 for 10 dof"}})");
    d.write("fast_time.csv", [] {
      std::string record = "t,x\n";
      for (int i = 0; i < 200; ++i) {
        record += std::to_string(i) + "e-12," + std::to_string((i * 7) % 5) + "\n";
      }
      return record;
    }());
    d.write("tiny.csv", [] {
      std::string record = "t,x\n";
      for (int i = 0; i < 200; ++i) {
        record += std::to_string(i) + "," + std::to_string((i * 7) % 5) + "e-170\n";
      }
      return record;
    }());
    // Misleading messages (issue #26 item 10).
    d.write("nul.csv", std::string("t,x\n0,1\n1,") + '\0' + "2\n2,3\n");
    fs::create_directories(d.path() / "folder.json.f64");
    d.write("duplicate_columns.csv", "t,x,x\n0,1,2\n1,2,3\n2,3,4\n3,4,5\n");
    d.write("quoted_header.csv", [] {
      std::string record = "\"t\",\"x\"\n";
      for (int i = 0; i < 200; ++i) {
        record += std::to_string(i) + "," + std::to_string(i % 3) + "\n";
      }
      return record;
    }());
    d.write("long_cell.csv", "t,x\n0,1\n1," + std::string(1'000'000, '9') + "x\n2,3\n");
    const std::string axis =
        R"({"units": "deg/h", "rate_hz": 10, "terms": [{"type": "angle_random_walk", "N": 0.1}]})";
    d.write("axes.json", R"({"axes": {"x": )" + axis + R"(, "y": )" + axis + "}}");
    // A socket: no output may be written there.
    const int socket_fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    const std::string socket_path = d.file("socket");
    if (socket_path.size() < sizeof address.sun_path) {
      std::memcpy(address.sun_path, socket_path.c_str(), socket_path.size() + 1);
      if (::bind(socket_fd, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0) {
        setup_error_ = "cannot make a socket";
      }
    }
    ::close(socket_fd);
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  void SetUp() override {
    if (!setup_error_.empty()) GTEST_SKIP() << "simulating the scenario failed: " << setup_error_;
  }

  static TempDir* dir_;
  static std::string setup_error_;
};
TempDir* Catalogue::dir_ = nullptr;
std::string Catalogue::setup_error_;

bool has_raw_control_character(const std::string& line) {
  for (std::size_t i = 0; i + 1 < line.size(); ++i) {
    const auto byte = static_cast<unsigned char>(line[i]);
    if (byte < 0x20 || byte == 0x7f) return true;
  }
  return false;
}

std::vector<std::string> temporary_files(const fs::path& root) {
  std::vector<std::string> found;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    const std::string name = entry.path().filename().string();
    if (name.find(".tmp") != std::string::npos || name == ".scenarios" ||
        name.rfind(".diagnose-staging", 0) == 0) {
      found.push_back(entry.path().string());
    }
  }
  return found;
}

TEST_P(Catalogue, HandledAsDocumented) {
  const CatalogueCase& c = GetParam();
  const std::string dir = dir_->path().string();
  const CliResult result =
      run_in_shell(replace_at(c.shell_prefix, dir), replace_at(c.arguments, dir), dir);
  EXPECT_EQ(result.exit_code, c.exit_code) << result.err;
  if (c.exit_code == 0) {
    EXPECT_NE(result.out.find(c.fragment), std::string::npos) << result.out;
  } else {
    ASSERT_FALSE(result.err.empty());
    EXPECT_EQ(result.err.find('\n'), result.err.size() - 1) << "one line: " << result.err;
    EXPECT_NE(result.err.find(c.fragment), std::string::npos) << result.err;
    EXPECT_FALSE(has_raw_control_character(result.err)) << result.err;
    EXPECT_EQ(result.err.find("internal error"), std::string::npos) << result.err;
    // "fit_noise_terms: ..." and the like: a snake_case identifier used as a message prefix.
    static const std::regex kInternalName("(^|: )[a-z]+_[a-z_]+: ");
    EXPECT_FALSE(std::regex_search(result.err, kInternalName)) << result.err;
  }
  for (const std::string& path : c.absent) {
    EXPECT_FALSE(fs::exists(replace_at(path, dir))) << "left behind: " << path;
  }
  EXPECT_EQ(temporary_files(dir_->path()), std::vector<std::string>{});
}

// Each case names the defect of issue #17 it checks.
INSTANTIATE_TEST_SUITE_P(
    Issue17, Catalogue,
    ::testing::Values(
        // Silent wrong results.
        CatalogueCase{"column_index_overflow",
                      "allan --input @/good.csv --rate 1 --column 99999999999999999999999", 2,
                      "column index 99999999999999999999999 out of range"},
        CatalogueCase{"negative_seed_simulate_noise",
                      "simulate noise --model @/model.json --duration 10 --rate 10 --seed -5 "
                      "--out @/n.csv",
                      2,
                      "--seed",
                      {"@/n.csv"}},
        CatalogueCase{"negative_seed_simulate_scenario",
                      "simulate scenario @/scenario.json --seed -1 --out @/s",
                      2,
                      "--seed",
                      {"@/s"}},
        CatalogueCase{"negative_seed_diagnose",
                      "diagnose --input @/good.csv --model @/model.json --seed -1 --out @/d",
                      2,
                      "--seed",
                      {"@/d"}},
        CatalogueCase{"negative_seeds_compare",
                      "compare @/experiment.json --seeds 2 -3 --out @/c",
                      2,
                      "--seeds",
                      {"@/c"}},
        CatalogueCase{"alternating_1e308_refused", "allan --input @/alternating.csv --format json",
                      2, "alternating.csv:2: column 'x': -1e+308 is beyond +/-1e100"},
        CatalogueCase{"run_imu_gap",
                      "run @/run.json --data @/gap --out @/r",
                      2,
                      "imu.csv:1002: IMU time step",
                      {"@/r"}},
        CatalogueCase{"run_imu_rate_change",
                      "run @/run.json --data @/rate_change --out @/r",
                      2,
                      "imu.csv:1502: IMU time step",
                      {"@/r"}},
        CatalogueCase{"run_non_finite_solution",
                      "run @/run.json --data @/spike --out @/r",
                      2,
                      "not finite from t = 7.01 s",
                      {"@/r"}},
        CatalogueCase{"simulate_noise_infinite",
                      "simulate noise --model @/model_huge.json --duration 10 --rate 10 --seed 1 "
                      "--out @/n.csv",
                      2,
                      "model_huge.json: the simulated value is not finite",
                      {"@/n.csv"}},
        CatalogueCase{"cr_only_line_endings", "allan --input @/cr_only.csv", 2,
                      "cr_only.csv:1: carriage return (CR)"},
        CatalogueCase{"bom_is_not_part_of_the_header", "allan --input @/bom.csv --format csv", 0,
                      "m,tau,n"},
        CatalogueCase{"crlf_line_endings", "allan --input @/crlf.csv --format csv", 0, "\n1,1,7,"},
        // Exit 1 instead of 2.
        CatalogueCase{"json_1e400_simulate",
                      "simulate noise --model @/model_1e400.json --duration 10 --rate 10 --seed 1 "
                      "--out @/n.csv",
                      2,
                      "model_1e400.json: a number is out of range",
                      {"@/n.csv"}},
        CatalogueCase{"json_1e400_diagnose",
                      "diagnose --input @/good.csv --model @/model_1e400.json --out @/d",
                      2,
                      "model_1e400.json: a number is out of range",
                      {"@/d"}},
        CatalogueCase{"json_1e400_run",
                      "run @/run_1e400.json --out @/r",
                      2,
                      "run_1e400.json: a number is out of range",
                      {"@/r"}},
        CatalogueCase{"json_1e400_compare",
                      "compare @/experiment_1e400.json --out @/c",
                      2,
                      "experiment_1e400.json: a number is out of range",
                      {"@/c"}},
        CatalogueCase{"json_1e400_scenario",
                      "simulate scenario @/scenario_1e400.json --out @/s",
                      2,
                      "scenario_1e400.json: a number is out of range",
                      {"@/s"}},
        CatalogueCase{"subnormal_in_scenario_works",
                      "simulate scenario @/scenario_subnormal.json --out @/sub", 0, ""},
        CatalogueCase{"folder_as_model_diagnose",
                      "diagnose --input @/good.csv --model @/folder.json --out @/d",
                      2,
                      "folder.json: is a folder",
                      {"@/d"}},
        CatalogueCase{"folder_as_model_simulate",
                      "simulate noise --model @/folder.json --duration 1 --rate 10 --seed 1 "
                      "--out @/n.csv",
                      2,
                      "folder.json: is a folder",
                      {"@/n.csv"}},
        CatalogueCase{"folder_as_run_config",
                      "run @/folder.json --out @/r",
                      2,
                      "folder.json: is a folder",
                      {"@/r"}},
        CatalogueCase{"folder_as_experiment",
                      "compare @/folder.json --out @/c",
                      2,
                      "folder.json: is a folder",
                      {"@/c"}},
        CatalogueCase{"folder_as_scenario",
                      "simulate scenario @/folder.json --out @/s",
                      2,
                      "folder.json: is a folder",
                      {"@/s"}},
        // Messages.
        CatalogueCase{"broken_plugin_library",
                      "run @/run_broken_plugin.json --out @/r",
                      2,
                      "noise plugin type 'mymodel' is not available: ",
                      {"@/r"}},
        CatalogueCase{"write_failure_reports_errno",
                      "simulate noise --model @/model.json --duration 1000 --rate 10 --seed 1 "
                      "--out @/n.csv",
                      2,
                      "n.csv: cannot write (File too large)",
                      {"@/n.csv"},
                      "ulimit -f 8; trap '' XFSZ"},
        CatalogueCase{"control_characters_escaped", "allan --input @/control.csv", 2,
                      "'2\\x1b[31mred\\x07' in column 'x'"},
        CatalogueCase{"no_internal_function_name",
                      "diagnose --input @/good.csv --model @/model_subnormal.json --plots none "
                      "--out @/d",
                      2,
                      "the noise model's Allan variance is 0",
                      {"@/d"}},
        // Bounded work.
        CatalogueCase{"simulate_duration_1e12",
                      "simulate noise --model @/model.json --duration 1e12 --rate 10 --seed 1 "
                      "--out @/n.csv",
                      2,
                      "above the limit of 1e+09",
                      {"@/n.csv"}},
        CatalogueCase{"simulate_rate_1e9",
                      "simulate noise --model @/model.json --duration 10 --rate 1e9 --seed 1 "
                      "--out @/n.csv",
                      2,
                      "above the limit of 1e+06 Hz",
                      {"@/n.csv"}},
        CatalogueCase{"scenario_duration_1e12",
                      "simulate scenario @/scenario_1e12.json --out @/s",
                      2,
                      "the limit on work",
                      {"@/s"}},
        CatalogueCase{"compare_1e6_seeds",
                      "compare @/experiment_1e6_seeds.json --out @/c",
                      2,
                      "above the limit of 1000",
                      {"@/c"}},
        CatalogueCase{"diagnose_1e6_seeds",
                      "diagnose --input @/good.csv --model @/model.json --seeds 1000000 "
                      "--out @/d",
                      2,
                      "above the limit of 1000",
                      {"@/d"}},
        CatalogueCase{"diagnose_iterations",
                      "diagnose --input @/good.csv --model @/model.json --max-iterations 1000000 "
                      "--out @/d",
                      2,
                      "above the limit of 32",
                      {"@/d"}}),
    [](const ::testing::TestParamInfo<CatalogueCase>& case_info) { return case_info.param.name; });

constexpr const char* kFull = "exec >/dev/full";
constexpr const char* kStdoutFull = "standard output: cannot write (No space left on device); ";

// Issue #26: write errors are never ignored (standard output included), outputs never replace
// a special file, and inputs are checked whole (gzip to its end, truth in time order, JSON
// without duplicate keys).
INSTANTIATE_TEST_SUITE_P(
    Issue26, Catalogue,
    ::testing::Values(
        // Every write and the final flush of standard output is checked.
        CatalogueCase{"allan_stdout_full", "allan --input @/good.csv", 2, kStdoutFull, {}, kFull},
        CatalogueCase{"allan_json_stdout_full", "allan --input @/good.csv --format json", 2,
                      kStdoutFull, {}, kFull},
        CatalogueCase{"davar_stdout_full", "davar --input @/good.csv --window 50 --step 25", 2,
                      kStdoutFull, {}, kFull},
        CatalogueCase{"fit_stdout_full", "fit --input @/good.csv --format json", 2, kStdoutFull,
                      {}, kFull},
        CatalogueCase{"plugins_list_stdout_full", "plugins list", 2, kStdoutFull, {}, kFull},
        CatalogueCase{"run_stdout_full", "run @/run.json --out @/run_full --no-plot", 2,
                      kStdoutFull, {}, kFull},
        CatalogueCase{"help_stdout_full", "--help", 2, kStdoutFull, {}, kFull},
        CatalogueCase{"allan_stdout_closed", "allan --input @/good.csv", 2,
                      "standard output: cannot write (Bad file descriptor)", {}, "exec >&-"},
        CatalogueCase{"run_stdout_closed", "run @/run.json --out @/run_closed --no-plot", 2,
                      "standard output: cannot write (Bad file descriptor)", {}, "exec >&-"},
        // (ulimit -f 8: a few KB, room for the one line on stderr, not for the output.)
        CatalogueCase{"allan_stdout_file_too_large", "allan --input @/long.csv --taus all", 2,
                      "standard output: cannot write (File too large)", {},
                      "ulimit -f 8; trap '' XFSZ; exec >'@/stdout.txt'"},
        CatalogueCase{"allan_output_file_too_large",
                      "allan --input @/long.csv --taus all --output @/allan.csv", 2,
                      "allan.csv: cannot write (File too large)", {"@/allan.csv"},
                      "ulimit -f 8; trap '' XFSZ"},
        CatalogueCase{"davar_output_file_too_large",
                      "davar --input @/long.csv --window 50 --step 5 --output @/davar.csv", 2,
                      "davar.csv: cannot write (File too large)", {"@/davar.csv"},
                      "ulimit -f 8; trap '' XFSZ"},
        CatalogueCase{"run_output_file_too_large", "run @/run.json --out @/run_big --no-plot", 2,
                      "cannot write (File too large)", {"@/run_big"}, "ulimit -f 8; trap '' XFSZ"},
        // A special file is not replaced.
        CatalogueCase{"output_is_a_folder", "allan --input @/good.csv --output @/folder.json", 2,
                      "folder.json: is a folder; an output must be a regular file"},
        CatalogueCase{"output_is_a_socket", "allan --input @/good.csv --output @/socket", 2,
                      "socket: is a socket; an output must be a regular file"},
        // gzip checked to the end.
        CatalogueCase{"gzip_whole", "allan --input @/record.txt.gz --rate 100 --format csv", 0,
                      "m,tau,n"},
        CatalogueCase{"gzip_truncated", "allan --input @/truncated.txt.gz --rate 100", 2,
                      "truncated.txt.gz: truncated gzip file (unexpected end of file)"},
        CatalogueCase{"gzip_corrupt", "allan --input @/corrupt.txt.gz --rate 100", 2,
                      "corrupt.txt.gz: corrupt gzip data (incorrect data check)"},
        CatalogueCase{"gzip_no_header", "allan --input @/headerless.txt.gz --rate 100", 2,
                      "headerless.txt.gz: not a gzip file"},
        // truth.csv in time order.
        CatalogueCase{"run_truth_swapped",
                      "run @/run.json --data @/truth_swapped --out @/r",
                      2,
                      "truth.csv:153: time does not increase",
                      {"@/r"}},
        CatalogueCase{"run_truth_duplicated",
                      "run @/run.json --data @/truth_duplicated --out @/r",
                      2,
                      "truth.csv:203: time does not increase",
                      {"@/r"}},
        // Duplicate JSON keys, with their pointer, in every config.
        CatalogueCase{"duplicate_key_model",
                      "simulate noise --model @/model_duplicate.json --duration 10 --rate 10 "
                      "--seed 1 --out @/n.csv",
                      2,
                      "model_duplicate.json: duplicate key at /terms/0/N;",
                      {"@/n.csv"}},
        CatalogueCase{"duplicate_key_diagnose_model",
                      "diagnose --input @/good.csv --model @/model_duplicate.json --out @/d",
                      2,
                      "model_duplicate.json: duplicate key at /terms/0/N;",
                      {"@/d"}},
        CatalogueCase{"duplicate_key_run",
                      "run @/run_duplicate.json --out @/r",
                      2,
                      "run_duplicate.json: duplicate key at /aids/0/plugin;",
                      {"@/r"}},
        CatalogueCase{"duplicate_key_experiment",
                      "compare @/experiment_duplicate.json --out @/c",
                      2,
                      "experiment_duplicate.json: duplicate key at /baseline;",
                      {"@/c"}},
        CatalogueCase{"duplicate_key_scenario",
                      "simulate scenario @/scenario_duplicate.json --out @/s",
                      2,
                      "scenario_duplicate.json: duplicate key at /vibration_table/phases/0/duration_s;",
                      {"@/s"}},
        // A failed fit is exit 2 naming the term and why, unless --keep-failed (flagged).
        CatalogueCase{"fit_failed",
                      "fit --input @/sinusoid.csv --terms angle_random_walk --format json "
                      "--output @/f.json",
                      2,
                      "sinusoid.csv: fit failed: chi-square",
                      {"@/f.json"}},
        CatalogueCase{"fit_failed_kept",
                      "fit --input @/sinusoid.csv --terms angle_random_walk --format json "
                      "--keep-failed",
                      0, "\"failed\": true"},
        CatalogueCase{"fit_terms_empty", "fit --input @/good.csv --terms ''", 2,
                      "--terms: no term named"},
        CatalogueCase{"fit_terms_twice",
                      "fit --input @/good.csv --terms angle_random_walk,angle_random_walk", 2,
                      "--terms: angle_random_walk is given twice"},
        // simulate noise refuses a model flagged as a failed fit unless told.
        CatalogueCase{"simulate_failed_fit",
                      "simulate noise --model @/failed_fit.json --duration 10 --rate 10 --seed 1 "
                      "--out @/n.csv",
                      2,
                      "failed_fit.json: /diagnostics/failed: the model is a failed fit "
                      "(chi-square 2671 for 10 dof); refit the record, or give --accept-failed",
                      {"@/n.csv"}},
        CatalogueCase{"simulate_failed_fit_accepted",
                      "simulate noise --model @/failed_fit.json --duration 10 --rate 10 --seed 1 "
                      "--accept-failed --out @/accepted.csv",
                      0, ""},
        CatalogueCase{"simulate_column_t",
                      "simulate noise --model @/model.json --duration 10 --rate 10 --seed 1 "
                      "--column t --out @/n.csv",
                      2, "--column t: the name of the time column", {"@/n.csv"}},
        // Absurd rates and magnitudes, refused up front.
        CatalogueCase{"allan_rate_1e_minus_320", "allan --input @/record.txt --rate 1e-320", 2,
                      "--rate 9.99989e-321 Hz is outside [1e-09, 1e+09] Hz"},
        CatalogueCase{"allan_rate_1e308", "allan --input @/record.txt --rate 1e308", 2,
                      "--rate 1e+308 Hz is outside [1e-09, 1e+09] Hz"},
        CatalogueCase{"davar_rate_1e308",
                      "davar --input @/record.txt --rate 1e308 --window 100 --step 50", 2,
                      "--rate 1e+308 Hz is outside"},
        CatalogueCase{"fit_rate_1e_minus_320", "fit --input @/record.txt --rate 1e-320", 2,
                      "Hz is outside [1e-09, 1e+09] Hz"},
        CatalogueCase{"allan_time_column_1e12_hz", "allan --input @/fast_time.csv", 2,
                      "fast_time.csv: the time column's rate 1e+12 Hz is outside"},
        CatalogueCase{"allan_values_1e_minus_170", "allan --input @/tiny.csv", 2,
                      "tiny.csv: the largest sample magnitude is 4e-170, below 1e-100"},
        // The streaming readers (wv, the causal DAVAR) check it too (SampleReader).
        CatalogueCase{"wv_values_1e_minus_170", "wv --input @/tiny.csv", 2,
                      "tiny.csv: the largest sample magnitude is 4e-170, below 1e-100"},
        CatalogueCase{"causal_davar_values_1e_minus_170",
                      "davar --input @/tiny.csv --window 20 --step 10 --causal", 2,
                      "tiny.csv: the largest sample magnitude is 4e-170, below 1e-100"},
        // Item 10: messages that said the wrong thing, or too much.
        CatalogueCase{"nul_byte_in_record", "allan --input @/nul.csv", 2,
                      "nul.csv:3: a NUL byte in column 'x': the file holds binary data, not text"},
        CatalogueCase{"folder_as_record", "allan --input @/folder.json --rate 1", 2,
                      "folder.json: is a folder, not a record file"},
        CatalogueCase{"folder_as_binary_record", "fit --input @/folder.json.f64 --rate 1", 2,
                      "folder.json.f64: is a folder, not a record file"},
        CatalogueCase{"davar_window_2_pow_64_minus_1",
                      "davar --input @/good.csv --window 18446744073709551615 --step 1", 2,
                      "--window 18446744073709551615 is longer than any record can be"},
        CatalogueCase{"plugins_check_imu_rate_0",
                      "plugins check @/stochnav_noise_mymodel.so --imu-rate 0", 2,
                      "--imu-rate: '0' is not a positive, finite number"},
        CatalogueCase{"diagnose_seeds_1",
                      "diagnose --input @/good.csv --model @/model.json --seeds 1 --out @/d", 2,
                      "--seeds 1; expected 0 (no simulated band) or 2 to 1000", {"@/d"}},
        CatalogueCase{"csv_duplicate_column_names", "allan --input @/duplicate_columns.csv", 2,
                      "duplicate_columns.csv:1: the header names column 'x' twice (columns 1 and "
                      "2)"},
        CatalogueCase{"csv_quoted_header_names",
                      "allan --input @/quoted_header.csv --column x --format csv", 0, "m,tau,n"},
        CatalogueCase{"long_cell_echo_cut", "allan --input @/long_cell.csv", 2,
                      "'999999999999999999999999999999999999999999999999999999999999... "
                      "(1000001 characters)' in column 'x' is not a number"},
        CatalogueCase{"simulate_column_twice",
                      "simulate noise --model @/axes.json --duration 10 --rate 10 --seed 1 "
                      "--column x --column x --out @/n.csv",
                      2, "--column x: given to two axes", {"@/n.csv"}}),
    [](const ::testing::TestParamInfo<CatalogueCase>& case_info) { return case_info.param.name; });

// Issue #30 item 3: steering a fit (--start, --fix, --bound), both methods: a bad control is
// exit 2 with one line naming the option and the parameter.
constexpr const char* kSteeredFit =
    "fit --input @/good.csv --terms angle_random_walk,gauss_markov --output @/f.json ";
INSTANTIATE_TEST_SUITE_P(
    Issue30, Catalogue,
    ::testing::Values(
        CatalogueCase{"fit_start_unknown_term",
                      std::string(kSteeredFit) + "--start drift.tau_c=1",
                      2,
                      "--start 'drift.tau_c=1': unknown term 'drift'",
                      {"@/f.json"}},
        CatalogueCase{"fit_fix_term_not_in_model",
                      std::string(kSteeredFit) + "--fix rate_random_walk.K=1",
                      2,
                      "--fix 'rate_random_walk.K=1': the model has 0 rate_random_walk term(s)",
                      {"@/f.json"}},
        CatalogueCase{"fit_fix_parameter_not_in_term",
                      std::string(kSteeredFit) + "--fix angle_random_walk.tau_c=1",
                      2,
                      "--fix 'angle_random_walk.tau_c=1': angle_random_walk has no parameter "
                      "'tau_c'; it has N",
                      {"@/f.json"}},
        CatalogueCase{"fit_bound_low_above_high",
                      std::string(kSteeredFit) + "--bound gauss_markov.tau_c=10:1",
                      2,
                      "--bound gauss_markov.tau_c: LOW is not below HIGH",
                      {"@/f.json"}},
        CatalogueCase{"fit_fix_outside_bound",
                      std::string(kSteeredFit) +
                          "--fix gauss_markov.tau_c=100 --bound gauss_markov.tau_c=1:10",
                      2,
                      "--fix gauss_markov.tau_c: is outside its bound",
                      {"@/f.json"}},
        CatalogueCase{"fit_fix_every_parameter",
                      std::string(kSteeredFit) +
                          "--fix angle_random_walk.N=1,gauss_markov.sigma=1,gauss_markov.tau_c=1",
                      2,
                      "--fix: every parameter of the model is fixed",
                      {"@/f.json"}},
        CatalogueCase{"fit_fix_every_parameter_gmwm",
                      "fit --method gmwm --input @/good.csv --terms angle_random_walk "
                      "--fix angle_random_walk.N=1 --output @/f.json",
                      2,
                      "--fix: every parameter of the model is fixed",
                      {"@/f.json"}},
        CatalogueCase{"fit_steering_without_terms",
                      "fit --input @/good.csv --start gauss_markov.tau_c=1 --output @/f.json",
                      2,
                      "--start/--fix/--bound steer the terms of --terms",
                      {"@/f.json"}},
        CatalogueCase{"fit_start_not_a_number",
                      std::string(kSteeredFit) + "--start gauss_markov.tau_c=x",
                      2,
                      "--start 'gauss_markov.tau_c=x': 'x' is not a number",
                      {"@/f.json"}}),
    [](const ::testing::TestParamInfo<CatalogueCase>& case_info) { return case_info.param.name; });

// Issue #26 item 10: an error message echoes at most 60 characters of a cell; a 1 MB cell gave a
// 1 MB line.
TEST_F(Catalogue, EchoedCellsAreCut) {
  const std::string dir = dir_->path().string();
  const CliResult result = testing::run_cli(replace_at("allan --input @/long_cell.csv", dir), dir);
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_LT(result.err.size(), 400u) << result.err.substr(0, 400);
}

// `stochnav ARGUMENTS > stdout_path` on a pseudo-terminal (script(1)): what it drew there.
std::string run_on_terminal(const std::string& arguments, const std::string& stdout_path) {
  const std::string inner =
      std::string("'") + STOCHNAV_CLI_PATH + "' " + arguments + " > '" + stdout_path + "'";
  std::string quoted;
  for (char c : inner) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  const std::string command = "script -qec '" + quoted + "' /dev/null";
  std::string drawn;
  std::FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return drawn;
  std::array<char, 4096> chunk{};
  while (std::fgets(chunk.data(), chunk.size(), pipe) != nullptr) drawn += chunk.data();
  ::pclose(pipe);
  return drawn;
}

std::string file_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// Issue #26: allan, davar, fit and diagnose draw a progress bar on a terminal's standard error,
// and print nothing on stderr into a file or a pipe; standard output is byte for byte the same.
TEST_F(Catalogue, ProgressBarsOnlyOnATerminal) {
  if (std::system("command -v script > /dev/null 2>&1") != 0) GTEST_SKIP() << "no script(1)";
  const std::string dir = dir_->path().string();
  struct Case {
    std::string arguments;
    std::string bar;  ///< the start of the progress line drawn
  };
  const std::vector<Case> cases = {
      {"allan --input @/long.csv --format csv", "allan: reading ["},
      {"davar --input @/long.csv --window 100 --step 50", "davar ["},
      {"fit --input @/long.csv --format json", "fit: reading ["},
      {"fit --input @/long.csv --window 500 --step 250 --terms angle_random_walk --keep-failed",
       "fit: windows ["},
      {"diagnose --input @/long.csv --model @/model.json --plots none --out @/progress",
       "diagnose ["},
  };
  for (const Case& c : cases) {
    const std::string arguments = replace_at(c.arguments, dir);
    const CliResult plain = testing::run_cli(arguments, dir);
    EXPECT_EQ(plain.exit_code, 0) << arguments << ": " << plain.err;
    EXPECT_EQ(plain.err, "") << arguments;
    const std::string drawn = run_on_terminal(arguments, dir + "/terminal_stdout.txt");
    EXPECT_NE(drawn.find(c.bar), std::string::npos) << arguments << ": " << drawn;
    EXPECT_NE(drawn.find("100.0 %"), std::string::npos) << arguments << ": " << drawn;
    EXPECT_EQ(file_text(dir + "/terminal_stdout.txt"), plain.out) << arguments;
  }
  fs::remove(dir + "/terminal_stdout.txt");
}

// Issue #26: the sinusoid fit finds a clean sinusoid (it returned A = 0.70, f = 0.0715 Hz).
TEST_F(Catalogue, FitFindsACleanSinusoid) {
  const std::string dir = dir_->path().string();
  const CliResult result = testing::run_cli(
      replace_at("fit --input @/sinusoid.csv --unit deg/h --terms sinusoid --format json", dir),
      dir);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const nlohmann::json fit = nlohmann::json::parse(result.out);
  ASSERT_EQ(fit["terms"].size(), 1u) << result.out;
  EXPECT_NEAR(fit["terms"][0]["amplitude"].get<double>(), 1.0, 0.01) << result.out;
  EXPECT_NEAR(fit["terms"][0]["frequency_hz"].get<double>(), 0.05, 0.0005) << result.out;
  EXPECT_FALSE(fit["diagnostics"]["failed"].get<bool>()) << result.out;
}

TEST_F(Catalogue, SubnormalScenarioIsWrittenWhole) {
  const std::string dir = dir_->path().string();
  const CliResult result = testing::run_cli(
      replace_at("simulate scenario @/scenario_subnormal.json --out @/subnormal", dir), dir);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const nlohmann::json written = read_json(dir_->path() / "subnormal" / "scenario.json");
  EXPECT_NE(written.dump().find("angle_random_walk"), std::string::npos);
}

// Issue #26: an output named through a symbolic link replaces the link's target; the link stays.
TEST_F(Catalogue, OutputThroughASymlinkReplacesItsTarget) {
  const TempDir& d = *dir_;
  fs::create_directories(d.path() / "linked");
  d.write("linked/allan.csv", "old\n");
  fs::create_symlink("linked/allan.csv", d.path() / "allan_link.csv");
  const CliResult result = testing::run_cli(
      replace_at("allan --input @/good.csv --format csv --output @/allan_link.csv",
                 d.path().string()),
      d.path().string());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_TRUE(fs::is_symlink(d.path() / "allan_link.csv"));
  std::ifstream written(d.path() / "linked" / "allan.csv");
  std::string header;
  std::getline(written, header);
  EXPECT_EQ(header.rfind("m,tau,n", 0), 0u) << header;
  EXPECT_EQ(temporary_files(d.path()), std::vector<std::string>{});
}

// Issue #26: a FIFO named as the output is written into, not replaced by a regular file.
TEST_F(Catalogue, OutputToAFifoIsStreamedInPlace) {
  const TempDir& d = *dir_;
  const fs::path fifo = d.path() / "allan.fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::string read;
  std::thread reader([&] {
    std::ifstream in(fifo);
    read.assign(std::istreambuf_iterator<char>(in), {});
  });
  const CliResult result = testing::run_cli(
      replace_at("allan --input @/good.csv --format csv --output @/allan.fifo",
                 d.path().string()),
      d.path().string());
  reader.join();
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(read.rfind("m,tau,n", 0), 0u) << read;
  EXPECT_EQ(fs::status(fifo).type(), fs::file_type::fifo);
  fs::remove(fifo);
}

// Issue #26: temporary files a killed process left (NAME.tmpPID_N) are removed by the next run
// into the folder; those of a live process are not.
TEST_F(Catalogue, StaleTemporariesAreRemovedByTheNextRun) {
  const TempDir& d = *dir_;
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  int status = 0;
  ::waitpid(child, &status, 0);  // `child` is now a process id nobody has
  const fs::path out = d.path() / "stale_run";
  fs::create_directories(out);
  const std::string dead = ".tmp" + std::to_string(child);
  const std::string live = ".tmp" + std::to_string(::getpid());
  d.write("stale_run/nav.csv" + dead + "_0", "half a file");
  d.write("stale_run/metrics.json" + dead + "_7", "{");
  d.write("stale_run/survey.csv" + live + "_0", "being written");
  const CliResult result = testing::run_cli(
      replace_at("run @/run.json --out @/stale_run --no-plot", d.path().string()),
      d.path().string());
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_FALSE(fs::exists(out / ("nav.csv" + dead + "_0")));
  EXPECT_FALSE(fs::exists(out / ("metrics.json" + dead + "_7")));
  EXPECT_TRUE(fs::exists(out / ("survey.csv" + live + "_0")));
  EXPECT_TRUE(fs::exists(out / "metrics.json"));
  fs::remove(out / ("survey.csv" + live + "_0"));
}

}  // namespace
}  // namespace stochnav
