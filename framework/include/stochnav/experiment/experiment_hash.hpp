#pragma once
// A fingerprint of an experiment as it will run, so that the shards of one sharded comparison
// can tell they belong together (experiment/shard_run.hpp) and a folder from another experiment
// is refused instead of merged.

#include <string>

#include "stochnav/experiment/experiment_config.hpp"

namespace stochnav {

/// 16 hex digits of a 64-bit FNV-1a hash over: the experiment document without "threads"
/// (threads do not change results), the seeds and scenario overrides in effect (after --seeds
/// and --full-scenario), and the scenario config's content (parsed, so formatting does not
/// count; its path when it cannot be read). Files the variants name (noise models, recorded
/// data) are not read.
std::string experiment_hash(const ExperimentConfig& config);

}  // namespace stochnav
