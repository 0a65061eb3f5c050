// `camsim dataset`: a manifest's items rendered into a dataset folder, one shard at a time
// (integrator/dataset/dataset_run.h; manifests: docs/dataset-format.md; clusters:
// docs/cluster.md).
//
//   camsim dataset MANIFEST -o DIR [--shard i/N | --shards N] [--resume] [--item N]
//                  [--threads N] [--check] [--ocio-config F] [--display D] [--view V] [--look L]
//   camsim dataset --status DIR
//
// The shard: --shard i/N; else Slurm's SLURM_ARRAY_TASK_ID − SLURM_ARRAY_TASK_MIN of
// SLURM_ARRAY_TASK_COUNT; else Kubernetes' JOB_COMPLETION_INDEX of --shards N (or
// CAMSIM_SHARD_COUNT); else 0/1, every item.
// Exit codes (the retry contract): 0 done; 2 bad input (never retry); 130 SIGINT, 143
// SIGTERM: interrupted (retry with --resume); 1 an item failed inside camsim.
#pragma once

#include <atomic>
#include <cstddef>
#include <iosfwd>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "sensor/base/share.h"

namespace camsim {

struct DatasetArgs {
  std::string manifest;
  std::string outputDir = "out";
  std::optional<Share> shard;  // --shard i/N
  std::optional<int> shards;   // --shards N (with JOB_COMPLETION_INDEX)
  std::optional<std::size_t> item;
  bool resume = false;
  bool check = false;
  bool help = false;
  std::optional<std::string> status;  // --status DIR
  int threads = 0;
  std::optional<double> maxMemoryGb;  // none: 75 % of physical memory (resource_guard.h)
  std::string ocioConfig, display, view, look;
};

// args[0] == "dataset". UsageError on bad usage.
DatasetArgs parseDatasetArgs(const std::vector<std::string>& args);
std::string datasetUsageText();

// The shard from the flags and the environment (above); UsageError when inconsistent. With
// `source`: where it came from, for the log ("--shard", "SLURM_ARRAY_TASK_ID", …; "" for
// the default 0/1).
Share resolveShard(const DatasetArgs& args, const std::map<std::string, std::string>& env,
                   std::string* source = nullptr);

// Runs the command. *signal holds the number of the signal that set *cancel (0: none).
int runDatasetCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& log,
                      const std::atomic<bool>* cancel = nullptr,
                      const std::atomic<int>* signal = nullptr);

}  // namespace camsim
