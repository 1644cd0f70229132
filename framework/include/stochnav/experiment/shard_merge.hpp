#pragma once
// `stochnav compare merge DIR`: the shards of a sharded comparison (experiment/shard_run.hpp,
// files in experiment/shard_files.hpp) combined into the files of the unsharded run —
// results.json, table.md and the plots in DIR (a sweep: DIR/level_<i>/ and DIR/sweep.json,
// sweep.png, sweep_pairs.png) — with every per-seed value bit for bit that of the unsharded run.
// Only "wall_seconds" differs: merged, it is the sum of the jobs' wall times on their shards
// (the time one such machine would have taken), not the time of one run.
//
// Everything is read and checked before anything is written; any problem is an InputError
// (exit 2) naming the folder or file and how to fix it, and nothing is written:
//   - DIR/shards/ missing or empty;
//   - an entry of DIR/shards/ that is not a shard folder (shard-K-of-N/), or a damaged file;
//   - shards of different experiments (experiment hash) or different splits (N);
//   - one job written by two shards;
//   - shards not started, failed or unfinished: the message names them and gives the command
//     that reruns them (--shard K/N --resume, which redoes only their missing jobs).

#include <cstddef>
#include <filesystem>
#include <string>

namespace stochnav {

struct MergeSummary {
  std::size_t shards = 0;
  std::size_t jobs = 0;
  bool sweep = false;
  std::string table;  ///< table.md of a plain experiment (empty for a sweep)
};

MergeSummary merge_shards(const std::filesystem::path& out_dir);

}  // namespace stochnav
