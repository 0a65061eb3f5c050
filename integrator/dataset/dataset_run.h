// runDataset(): a shard of a manifest's items rendered into one dataset folder, each item
// reproducible on its own and every interruption recoverable (docs/dataset-format.md,
// docs/cluster.md).
//
//   DIR/dataset.json             the manifest's name, hash and item count (for --status)
//   DIR/index.jsonl              one JSON line per item that ended (done or failed): item,
//                                status, parameters, files with their FNV-1a hashes,
//                                hash of the resolved item, seconds (wall) and
//                                render_seconds (in render()), shard
//   DIR/items/NNNNNN/            the item's capture (or sequence) outputs, written with
//                                reproducible bytes, plus scene.yaml (the resolved scene),
//                                params.json (what the item sets) and item.json (written
//                                last: hash, files, status)
//   DIR/.camsim-lock             an empty file whose record locks say which shards run
//                                (dataset_lock.h)
// An item is rendered into DIR/items/.NNNNNN.camsim-tmp-<pid>/ and renamed into place when
// complete, so a killed item leaves only that temporary folder; the next run of the shard
// that owns the item removes it. A second run of a shard that is running (or a run with
// another shard count) is refused: InputError naming DIR/.camsim-lock. A kill between an
// item's rename and its index line is repaired by the next --resume (item_writer.h).
//
// | option    | default | meaning                                                             |
// |-----------|---------|---------------------------------------------------------------------|
// | shard     | 0 of 1  | item i belongs to shard i mod count                                 |
// | resume    | false   | skip items whose item.json hash equals the item's and whose files    |
// |           |         | all exist                                                           |
// | only_item | none    | render just this item (it must belong to the shard)                 |
// | cancel    | none    | checked between tiles; the item in progress is dropped             |
// Every item of the manifest (not only the shard's) is resolved and loaded (on all cores)
// before the first renders, so bad input fails every shard alike, with nothing written.
// Pipelined: while item n renders, item n − 1 is written (a writer thread) and item n + 1
// loaded (a task); a frame sequence writes each frame as it finishes.
#pragma once

#include <atomic>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "integrator/dataset/item_check.h"  // checkDataset: what a run checks first
#include "integrator/dataset/manifest.h"
#include "sensor/base/share.h"
#include "sensor/io/picture_writer.h"

namespace camsim {

enum class ItemStatus { kDone, kSkipped, kFailed, kInterrupted };
const char* itemStatusName(ItemStatus status);

struct ItemReport {
  std::size_t index = 0;
  ItemStatus status = ItemStatus::kDone;
  double seconds = 0.0;        // the item's wall time: load, render, write, hash
  double renderSeconds = 0.0;  // of it in render() (a sequence: summed over frames)
  std::size_t files = 0;       // written
  std::string message;         // why it failed
};

struct DatasetRunOptions {
  std::filesystem::path directory;
  Share shard;  // item i belongs to shard i mod count
  bool resume = false;
  std::optional<std::size_t> onlyItem;
  int threads = 0;                    // 0: all cores
  std::optional<double> maxMemoryGb;  // per item; none: 75 % of physical memory
  PictureSettings picture;
  const std::atomic<bool>* cancel = nullptr;
  // Before any rendering: every item resolved (items checked, items of the manifest).
  std::function<void(std::size_t, std::size_t)> onChecked;
  // (items of the shard finished, items of the shard, the current item's fraction).
  std::function<void(std::size_t, std::size_t, double)> progress;
  std::function<void(const ItemReport&)> onItem;  // as each item ends
  // Before any rendering, if the folder cannot be locked (dataset_lock.h): why.
  std::function<void(const std::string&)> onWarning;
};

struct DatasetRunSummary {
  std::size_t items = 0;  // of this shard (or 1 with only_item)
  std::size_t done = 0, skipped = 0, failed = 0;
  bool cancelled = false;
  bool cancelledWhileChecking = false;         // before anything was written
  std::vector<std::filesystem::path> removed;  // temporaries of killed runs
  // Up-to-date items (--resume) whose index line was missing and has been appended.
  std::vector<std::size_t> reindexed;
};

// InputError (nothing written) for a bad manifest, scene or item, or an only_item outside
// the manifest or the shard. An item that fails while rendering is reported and the others
// go on.
DatasetRunSummary runDataset(const Manifest& manifest, const DatasetRunOptions& options);

// What `camsim dataset --status DIR` prints the numbers of.
struct DatasetStatus {
  std::size_t total = 0, done = 0, failed = 0, missing = 0, temporaries = 0;
  std::vector<std::size_t> failedItems, missingItems;
  // Done items (item.json in place) without a done line in index.jsonl: a run was killed
  // between the two; `--resume` adds the lines.
  std::vector<std::size_t> unindexedItems;
};
// InputError if DIR holds no dataset (no dataset.json).
DatasetStatus datasetStatus(const std::filesystem::path& directory);

}  // namespace camsim
