// stochnav plugins list | check LIB [--params JSON] | show CONFIG: what the plugin search path
// offers, whether one library loads (exit code 2 with the real reason when it does not) and, with
// --params, whether its factory builds a noise model that has every property of
// plugin/noise_model_checks.hpp, or an aid that has every property of plugin/aid_checks.hpp at
// a true state (--state) with aid data consistent with it (--aid-data), exit code 2 with one
// line naming the first failure (all of them listed on standard output); and the plugins a run
// config builds (validated, fitted where asked) with the error-state layout they give.

#include <fmt/format.h>

#include <array>
#include <filesystem>
#include <memory>
#include <optional>

#include "command_support.hpp"
#include "commands.hpp"
#include "plugins_doc.hpp"
#include "standard_output.hpp"
#include "stochnav/core/angles.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/ins/mwd_attitude.hpp"
#include "stochnav/io/json_document.hpp"
#include "stochnav/plugin/aid_checks.hpp"
#include "stochnav/plugin/noise_model_checks.hpp"
#include "stochnav/plugin/param_table.hpp"
#include "stochnav/plugin/plugin_registry.hpp"
#include "stochnav/plugin/run_config.hpp"
#include "stochnav/plugin/runtime.hpp"

namespace stochnav::cli {
namespace {

struct PluginsArguments {
  std::string config;                // a config file: its folder leads the search path
  std::string data;                  // show: a recording folder replacing the config's data
  std::vector<std::string> folders;  // extra folders, searched first
  std::string library;               // check: the library file
  std::string params;                // check: params of the factory (JSON text), "" for none
  std::string group = "gyro";        // check: sensor group of the model
  double imu_rate_hz = 100.0;        // check: NoiseModelContext::imu_rate_hz
  plugin::PropertyCheckOptions checks;
  std::string aid_data;     // check (aid): aids.csv consistent with the true state
  std::string state;        // check (aid): the true state (JSON text), "" for the default
  double at_s = 1.0;        // check (aid): a time with a measurement (s)
  double interval_s = 1.0;  // check (aid): interval of an interval aid (s)
};

// The true state of an aid check, in the units of a survey listing.
struct TrueState {
  double latitude_deg;
  double longitude_deg;
  double height_m;
  std::array<double, 3> v_n_mps;
  double axial_speed_mps;
  double inclination_deg;
  double azimuth_deg;
  double toolface_deg;
};

const plugin::ParamTable<TrueState> kTrueStateTable{
    scalar(&TrueState::latitude_deg, "latitude_deg", plugin::ParamUnit::fixed("deg"),
           plugin::Bound::kAny, 30.0, "geodetic latitude"),
    scalar(&TrueState::longitude_deg, "longitude_deg", plugin::ParamUnit::fixed("deg"),
           plugin::Bound::kAny, 100.0, "longitude"),
    scalar(&TrueState::height_m, "height_m", plugin::ParamUnit::fixed("m"), plugin::Bound::kAny,
           0.0, "height above the WGS-84 ellipsoid"),
    per_axis(&TrueState::v_n_mps, "v_n_mps", plugin::ParamUnit::fixed("m/s"), plugin::Bound::kAny,
             0.0, "velocity, ENU, besides the axial speed"),
    scalar(&TrueState::axial_speed_mps, "axial_speed_mps", plugin::ParamUnit::fixed("m/s"),
           plugin::Bound::kAny, 0.0, "speed along the tool axis (down the hole)"),
    scalar(&TrueState::inclination_deg, "inclination_deg", plugin::ParamUnit::fixed("deg"),
           plugin::Bound::kAny, 60.0, "inclination of the tool axis"),
    scalar(&TrueState::azimuth_deg, "azimuth_deg", plugin::ParamUnit::fixed("deg"),
           plugin::Bound::kAny, 45.0, "azimuth of the tool axis from true north"),
    scalar(&TrueState::toolface_deg, "toolface_deg", plugin::ParamUnit::fixed("deg"),
           plugin::Bound::kAny, 30.0, "high-side toolface"),
};

NavState true_state_of(const std::string& text) {
  const nlohmann::json json =
      text.empty() ? nlohmann::json::object() : parse_json_document(text, "--state");
  const TrueState s = kTrueStateTable.parse(json, "--state");
  NavState state;
  state.latitude_rad = s.latitude_deg * kRadPerDeg;
  state.longitude_rad = s.longitude_deg * kRadPerDeg;
  state.height_m = s.height_m;
  state.q_nb = quaternion_from_mwd(
      {s.inclination_deg * kRadPerDeg, s.toolface_deg * kRadPerDeg, s.azimuth_deg * kRadPerDeg});
  state.v_n = Eigen::Vector3d(s.v_n_mps[0], s.v_n_mps[1], s.v_n_mps[2]) +
              state.q_nb * Eigen::Vector3d::UnitZ() * s.axial_speed_mps;
  return state;
}

std::string row(const plugin::PluginDescriptor& plugin) {
  return fmt::format(
      "{:<6} {:<20} {:<4} {:<4} {}\n", plugin::plugin_kind_name(plugin.kind), plugin.type,
      plugin.api_version,
      plugin.kind == plugin::PluginKind::kNoiseModel ? (plugin.can_fit ? "yes" : "no") : "-",
      plugin.file.string());
}

constexpr const char* kHeader = "kind   type                 api  fit  file\n";

void run_list(const PluginsArguments& arguments) {
  std::vector<std::filesystem::path> path(arguments.folders.begin(), arguments.folders.end());
  const std::filesystem::path config_dir =
      arguments.config.empty() ? std::filesystem::path()
                               : std::filesystem::absolute(arguments.config).parent_path();
  for (auto& folder : plugin::default_search_path(config_dir)) path.push_back(std::move(folder));
  const plugin::PluginRegistry registry(path);
  std::string out = kHeader;
  for (const auto& descriptor : registry.plugins()) out += row(descriptor);
  std::string folders;
  for (const auto& folder : registry.search_path()) {
    folders += (folders.empty() ? "" : ":") + folder.string();
  }
  write_standard_output(out + "search path: " + folders + '\n');
  const auto& problems = registry.problems();
  if (problems.empty()) return;
  std::string message = problems.front().reason;
  if (problems.size() > 1) {
    message = fmt::format("{} plugin problems: ", problems.size());
    for (std::size_t i = 0; i < problems.size(); ++i) {
      message += (i == 0 ? "" : " | ") + problems[i].reason;
    }
  }
  throw ConfigError(message);
}

// The one JSON reader's checks (syntax, range, duplicate keys), as for a config file.
nlohmann::json parse_params_option(const std::string& text) {
  return parse_json_document(text, "--params");
}

// The failed property checks, if any: each one a line "failed: ..." of the report on standard
// output, and one error (exit code 2) naming the first and how many there are.
void report_failures(const std::string& where, const std::vector<std::string>& failures) {
  if (failures.empty()) return;
  std::string report;
  for (const std::string& failure : failures) report += "failed: " + failure + '\n';
  write_standard_output(report);
  if (failures.size() == 1) throw ConfigError(where + failures.front());
  throw ConfigError(fmt::format("{}{} property checks failed, the first: {}; all of them are "
                                "listed on standard output",
                                where, failures.size(), failures.front()));
}

// Builds the model with the library's factory and runs the property checks (report_failures).
void check_noise_model_properties(const PluginsArguments& arguments,
                                  const plugin::PluginDescriptor& descriptor) {
  const auto group = plugin::parse_sensor_group(arguments.group);
  if (!group) {
    throw ConfigError("--group: found '" + arguments.group + "'; expected gyro or accel");
  }
  if (const std::string reason = arguments.checks.invalid_reason(); !reason.empty()) {
    throw ConfigError("--times/--dt1/--dt2/--step: " + reason + "; give positive steps and times");
  }
  const plugin::PluginRegistry registry = plugin::PluginRegistry::of_file(arguments.library);
  plugin::NoiseModelContext context;
  context.group = *group;
  context.imu_rate_hz = arguments.imu_rate_hz;
  context.params_pointer = "--params";
  const auto build = [&](const nlohmann::json& params) {
    return registry.create_noise_model(descriptor.type, params, context, "--params");
  };
  const auto model = build(parse_params_option(arguments.params));
  const std::vector<std::string> failures =
      plugin::check_noise_model(*model, build, arguments.checks);
  report_failures(fmt::format("{} ({}): ", arguments.library, arguments.group), failures);
  std::string times;
  for (double t : arguments.checks.times_s)
    times += (times.empty() ? "" : ", ") + fmt::format("{}", t);
  write_standard_output("model: " + model->describe() +
                        "\nproperties: covariances, zero step, composition, stationarity, "
                        "params round trip hold at t = " + times + " s\n");
}

// Builds the aid with the library's factory on the aid data and runs the aid checks at the true
// state (report_failures).
void check_aid_properties(const PluginsArguments& arguments,
                          const plugin::PluginDescriptor& descriptor) {
  if (!(arguments.interval_s >= 0.0)) {
    throw ConfigError("--interval: found " + std::to_string(arguments.interval_s) +
                      "; expected a time >= 0 (s)");
  }
  const plugin::PluginRegistry registry = plugin::PluginRegistry::of_file(arguments.library);
  const plugin::AidData data =
      arguments.aid_data.empty() ? plugin::AidData() : plugin::read_aid_data(arguments.aid_data);
  plugin::AidContext context;
  context.params_pointer = "--params";
  context.data = &data;
  context.initial_state = true_state_of(arguments.state);
  context.config_dir = std::filesystem::current_path();
  const auto build = [&](const nlohmann::json& params) {
    return registry.create_aid(descriptor.type, params, context, "--params");
  };
  const nlohmann::json params = parse_params_option(arguments.params);
  const auto aid = build(params);
  NavState truth = context.initial_state;
  truth.t_s = arguments.at_s;
  const plugin::AidCheckCase at{
      truth, arguments.at_s,
      plugin::steady_imu_sample(truth, arguments.at_s,
                                aid->measures_interval_mean() ? arguments.interval_s : 0.0)};
  const std::vector<std::string> failures = plugin::check_aid(*aid, build, params, at);
  report_failures(fmt::format("{} (aid at t = {} s): ", arguments.library, arguments.at_s),
                  failures);
  write_standard_output(fmt::format(
      "aid: {}\nproperties: sizes, covariance, residual at the truth, jacobian, params round trip "
      "hold at t = {} s\n",
      aid->describe(), arguments.at_s));
}

void run_check(const PluginsArguments& arguments) {
  const auto descriptor = plugin::check_plugin_file(arguments.library);
  write_standard_output(std::string(kHeader) + row(descriptor) + "description: " +
                        descriptor.description + "\nbuilt against stochnav " +
                        std::string(descriptor.framework_version) + '\n');
  if (arguments.params.empty()) return;
  if (descriptor.kind == plugin::PluginKind::kAid) {
    check_aid_properties(arguments, descriptor);
    return;
  }
  check_noise_model_properties(arguments, descriptor);
}

void run_show(const PluginsArguments& arguments) {
  std::optional<plugin::DataConfig> data;
  if (!arguments.data.empty()) data = plugin::data_from_folder(arguments.data);
  const plugin::RunConfig config = plugin::read_run_config(arguments.config, data);
  const plugin::PluginRegistry registry(plugin::default_search_path(config.config_dir));
  const plugin::AidData aids =
      config.data.aids ? plugin::read_aid_data(*config.data.aids) : plugin::AidData();
  const plugin::RunPlugins plugins =
      plugin::build_run_plugins(config, registry, aids, NavState(), 0.0);
  std::string out;
  out += "noise gyro:  " + plugins.gyro->describe() + "\n";
  out += "noise accel: " + plugins.accel->describe() + "\n";
  for (const auto& aid : plugins.aids) out += "aid: " + aid->describe() + "\n";
  out += fmt::format("error state: {} states\n", plugins.layout.size());
  for (const auto& block : plugins.layout.blocks()) {
    out += fmt::format("  {:<36} offset {:>3}  size {}\n", block.name, block.offset, block.size);
  }
  write_standard_output(out);
}

}  // namespace

void add_plugins_command(CLI::App& app) {
  auto arguments = std::make_shared<PluginsArguments>();
  CLI::App* command = app.add_subcommand("plugins", "List or check plugin libraries");
  command->require_subcommand(1);
  CLI::App* list = command->add_subcommand(
      "list", "Every plugin on the search path: kind, type, API version, fit support, file");
  list->add_option("--config", arguments->config, "Config file whose folder leads the search path");
  list->add_option("--path", arguments->folders, "Extra plugin folders, searched first");
  list->callback([arguments] { run_list(*arguments); });
  CLI::App* check = command->add_subcommand("check", "Load one plugin library and report it");
  check->add_option("library", arguments->library, "Plugin library file (.so)")->required();
  check->add_option("--params", arguments->params,
                    "Build a noise model or an aid with these params (JSON) and check its "
                    "properties");
  check->add_option("--group", arguments->group, "Sensor group of the model: gyro or accel")
      ->capture_default_str();
  check->add_option("--imu-rate", arguments->imu_rate_hz, "IMU rate given to the factory (Hz)")
      ->capture_default_str()
      ->check(positive_number());
  check
      ->add_option("--times", arguments->checks.times_s,
                   "Start times of the checks (s); put a time-varying model's changes among them")
      ->delimiter(',')
      ->capture_default_str();
  check->add_option("--dt1", arguments->checks.dt1_s, "First of two composed steps (s)")
      ->capture_default_str();
  check->add_option("--dt2", arguments->checks.dt2_s, "Second composed step (s)")
      ->capture_default_str();
  check
      ->add_option("--step", arguments->checks.stationary_step_s,
                   "Step of the stationarity run (s); models on a grid (ar, arma) need a multiple")
      ->capture_default_str();
  check->add_option("--aid-data", arguments->aid_data,
                    "Aid: aid data (CSV with a column t) that the tool at --state measures");
  check->add_option("--state", arguments->state,
                    "Aid: the true state (JSON: latitude_deg, longitude_deg, height_m, v_n_mps, "
                    "axial_speed_mps, inclination_deg, azimuth_deg, toolface_deg); default at "
                    "rest at 30 N 100 E, inclination 60, azimuth 45, toolface 30 deg");
  check->add_option("--at", arguments->at_s, "Aid: a time with a measurement (s)")
      ->capture_default_str();
  check
      ->add_option("--interval", arguments->interval_s,
                   "Aid: for an interval aid (rop, pipe_length), the time since its previous "
                   "measurement epoch (s)")
      ->capture_default_str();
  check->callback([arguments] { run_check(*arguments); });
  CLI::App* show = command->add_subcommand(
      "show", "Validate a run config, build its plugins and print them and the state layout the "
              "navigator will use");
  show->add_option("config", arguments->config, "Run config (JSON)")->required();
  show->add_option("--data", arguments->data,
                   "Recording folder replacing the config's \"data\" (as for run)");
  show->callback([arguments] { run_show(*arguments); });
  add_plugins_doc_command(*command);
}

}  // namespace stochnav::cli
