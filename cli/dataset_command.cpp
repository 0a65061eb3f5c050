#include "cli/dataset_command.h"

#include <cstdlib>
#include <memory>
#include <ostream>

#include "cli/args.h"
#include "cli/command_line.h"
#include "integrator/capture/progress.h"
#include "integrator/dataset/dataset_item.h"
#include "integrator/dataset/dataset_run.h"
#include "sensor/base/input_error.h"
#include "sensor/io/picture_writer.h"

namespace camsim {
namespace {

std::size_t count(const std::string& flag, const std::string& text, std::size_t lo) {
  return static_cast<std::size_t>(parseInteger(flag, text, static_cast<std::int64_t>(lo), 1 << 30));
}

std::string itemList(const std::vector<std::size_t>& items) {
  std::string s;
  for (std::size_t i = 0; i < items.size() && i < 20; ++i)
    s += (i ? " " : "") + std::to_string(items[i]);
  if (items.size() > 20) s += " …";
  return s;
}

}  // namespace

namespace {

std::unique_ptr<CLI::App> datasetApp(DatasetArgs& a) {
  auto app = newCommandApp(
      "dataset",
      "Renders the items of MANIFEST (docs/dataset-format.md) into DIR:\n"
      "DIR/items/NNNNNN/ per item (its outputs, scene.yaml, params.json, item.json),\n"
      "DIR/index.jsonl (one line per item that ended), DIR/dataset.json. Every item is\n"
      "checked before the first renders; same manifest, seed and build: same bytes, on any\n"
      "shard. `camsim dataset --status DIR` summarises DIR instead.");
  app->add_option("manifest", a.manifest, "the dataset manifest")->type_name("MANIFEST");
  app->add_option("-o,--output", a.outputDir, "the dataset folder (created if missing)")
      ->type_name("DIR");
  app->add_option_function<std::string>(
         "--shard", [&a](const std::string& t) { a.shard = parseShareOption("--shard", t); },
         "render items i, i+N, i+2N, … (0 <= i < N); without it, Slurm's SLURM_ARRAY_TASK_ID - "
         "SLURM_ARRAY_TASK_MIN of SLURM_ARRAY_TASK_COUNT, or Kubernetes' JOB_COMPLETION_INDEX "
         "of --shards N (or CAMSIM_SHARD_COUNT); else all items")
      ->type_name("i/N");
  app->add_option_function<std::string>(
         "--shards",
         [&a](const std::string& t) {
           a.shards = static_cast<int>(parseInteger("--shards", t, 1, kMaxShareCount));
         },
         "the shard count, with JOB_COMPLETION_INDEX")
      ->type_name("N");
  app->add_flag("--resume", a.resume,
                "skip items whose outputs exist and whose recorded hash matches the item's "
                "resolved scene and camsim version; remove temporaries of killed runs and add "
                "the index lines they did not write");
  app->add_option_function<std::string>(
         "--item", [&a](const std::string& t) { a.item = count("--item", t, 0); },
         "render only item N (of this shard)")
      ->type_name("N");
  addThreadsOption(*app, a.threads, "the items' bytes do not depend on it");
  addMemoryLimitOption(*app, a.maxMemoryGb, "a dataset with an item");
  app->add_flag("--check", a.check,
                "check the manifest and every item, print the item count, render nothing");
  app->add_option_function<std::string>(
         "--status", [&a](const std::string& t) { a.status = t; },
         "summarise DIR: done, failed, missing items")
      ->type_name("DIR");
  addPictureOptions(*app, a.ocioConfig, a.display, a.view, a.look);
  app->footer(
      "Exit codes: 0 done, 2 bad input or the shard already running into DIR (do not\n"
      "retry), 130/143 interrupted by SIGINT/SIGTERM (retry with --resume), 1 an item\n"
      "failed inside camsim (docs/cluster.md).");
  return app;
}

}  // namespace

std::string datasetUsageText() {
  DatasetArgs a;
  return commandHelp(*datasetApp(a));
}

DatasetArgs parseDatasetArgs(const std::vector<std::string>& args) {
  DatasetArgs a;
  if (!parseCommand(*datasetApp(a), args)) {
    a.help = true;
    return a;
  }
  if (!a.status && a.manifest.empty())
    throw UsageError("camsim dataset needs a MANIFEST (or --status DIR)");
  if (a.status && !a.manifest.empty()) throw UsageError("--status DIR takes no manifest");
  if (a.shard && a.shards) throw UsageError("give --shard i/N or --shards N, not both");
  return a;
}

Share resolveShard(const DatasetArgs& args, const std::map<std::string, std::string>& env,
                   std::string* source) {
  auto get = [&](const char* name) -> std::optional<std::string> {
    const auto it = env.find(name);
    if (it == env.end() || it->second.empty()) return std::nullopt;
    return it->second;
  };
  auto from = [source](const char* name) {
    if (source) *source = name;
  };
  // A shard count from the environment, in Share's range.
  auto shardCount = [](const char* name, const std::string& text) {
    return static_cast<int>(parseInteger(name, text, 1, kMaxShareCount));
  };
  if (source) source->clear();
  if (args.shard) {
    from("--shard");
    return *args.shard;
  }
  Share s;
  if (auto id = get("SLURM_ARRAY_TASK_ID")) {
    const auto n = get("SLURM_ARRAY_TASK_COUNT");
    if (!n) throw UsageError("SLURM_ARRAY_TASK_ID is set but SLURM_ARRAY_TASK_COUNT is not");
    s.count = shardCount("SLURM_ARRAY_TASK_COUNT", *n);
    const std::size_t task = count("SLURM_ARRAY_TASK_ID", *id, 0);
    const std::size_t min = get("SLURM_ARRAY_TASK_MIN")
                                ? count("SLURM_ARRAY_TASK_MIN", *get("SLURM_ARRAY_TASK_MIN"), 0)
                                : 0;
    const auto shards = static_cast<std::size_t>(s.count);
    if (task < min || task - min >= shards)
      throw UsageError("array task " + *id + " is not in " + std::to_string(min) + ".." +
                       std::to_string(min + shards - 1) +
                       ": submit a contiguous array (--array=0-" + std::to_string(s.count - 1) +
                       ")");
    s.index = static_cast<int>(task - min);
    from("SLURM_ARRAY_TASK_ID");
  } else if (auto k = get("JOB_COMPLETION_INDEX")) {
    std::optional<int> n = args.shards;
    if (!n && get("CAMSIM_SHARD_COUNT"))
      n = shardCount("CAMSIM_SHARD_COUNT", *get("CAMSIM_SHARD_COUNT"));
    if (!n)
      throw UsageError(
          "JOB_COMPLETION_INDEX is set: give the shard count (--shards N or CAMSIM_SHARD_COUNT)");
    s.count = *n;
    s.index = static_cast<int>(parseInteger("JOB_COMPLETION_INDEX", *k, 0, s.count - 1));
    from("JOB_COMPLETION_INDEX");
  } else if (args.shards) {
    throw UsageError(
        "--shards N needs JOB_COMPLETION_INDEX (a Kubernetes Indexed Job); else use --shard i/N");
  }
  return s;
}

int runDatasetCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& log,
                      const std::atomic<bool>* cancel, const std::atomic<int>* signal) {
  const DatasetArgs a = parseDatasetArgs(args);
  // 128 + the signal that stopped the run (SIGINT when not known).
  const auto interrupted = [&] { return 128 + (signal && signal->load() ? signal->load() : 2); };
  if (a.help) {
    out << datasetUsageText();
    return 0;
  }
  if (a.status) {
    const DatasetStatus s = datasetStatus(*a.status);
    out << *a.status << ": " << s.total << " items: " << s.done << " done, " << s.failed
        << " failed, " << s.missing << " missing";
    if (s.temporaries) out << ", " << s.temporaries << " temporaries of killed runs";
    out << "\n";
    if (!s.failedItems.empty()) out << "failed: " << itemList(s.failedItems) << "\n";
    if (!s.missingItems.empty()) out << "missing: " << itemList(s.missingItems) << "\n";
    if (!s.unindexedItems.empty())
      out << "done but not in index.jsonl (a run was killed before writing their lines; "
             "--resume adds them): "
          << itemList(s.unindexedItems) << "\n";
    return s.done == s.total ? 0 : 1;
  }
  std::map<std::string, std::string> env;
  for (const char* name : {"SLURM_ARRAY_TASK_ID", "SLURM_ARRAY_TASK_COUNT", "SLURM_ARRAY_TASK_MIN",
                           "JOB_COMPLETION_INDEX", "CAMSIM_SHARD_COUNT"})
    if (const char* v = std::getenv(name)) env[name] = v;
  std::string shardSource;
  const Share shard = resolveShard(a, env, &shardSource);
  const Manifest manifest = loadManifest(a.manifest);

  DatasetRunOptions o;
  o.directory = a.outputDir;
  o.shard = shard;
  o.resume = a.resume;
  o.onlyItem = a.item;
  o.threads = a.threads;
  o.maxMemoryGb = a.maxMemoryGb;
  o.picture = {a.ocioConfig, {a.display, a.view, a.look}};
  o.cancel = cancel;
  (void)checkPictureSettings(o.picture);
  ProgressBar checking("checking " + std::to_string(manifest.items.size()) + " items");
  o.onChecked = [&](std::size_t done, std::size_t total) {
    checking.update(static_cast<int>(done), static_cast<int>(total));
  };
  if (a.check) {
    o.onlyItem.reset();
    // What a run checks, the same way.
    const bool checked = checkDataset(manifest, {o.onChecked, o.maxMemoryGb, o.threads, cancel});
    checking.finish();
    if (!checked) {
      log << "dataset " << manifest.file.filename().string()
          << ": interrupted while checking the items\n";
      return interrupted();
    }
    out << manifest.file.string() << ": " << manifest.items.size() << " items, all valid\n";
    return 0;
  }
  std::unique_ptr<ProgressBar> rendering;
  o.progress = [&](std::size_t done, std::size_t total, double fraction) {
    if (!rendering) {
      checking.finish();
      rendering = std::make_unique<ProgressBar>("dataset shard " + std::to_string(shard.index) +
                                                "/" + std::to_string(shard.count) + " (" +
                                                std::to_string(total) + " items)");
    }
    rendering->update(static_cast<int>(1000 * (static_cast<double>(done) + fraction)),
                      static_cast<int>(1000 * total));
  };
  o.onWarning = [&](const std::string& warning) { log << "camsim: warning: " << warning << "\n"; };
  o.onItem = [&](const ItemReport& r) {
    if (r.status == ItemStatus::kFailed)
      log << "item " << r.index << " failed: " << r.message << "\n";
  };
  const DatasetRunSummary s = runDataset(manifest, o);
  checking.finish();
  if (s.cancelledWhileChecking) {
    log << "dataset " << manifest.file.filename().string()
        << ": interrupted while checking the items (nothing written)\n";
    return interrupted();
  }
  if (rendering) rendering->finish();
  for (const auto& f : s.removed)
    log << "removed " << f.string() << " (left by a run that was killed)\n";
  if (!s.reindexed.empty())
    log << "index.jsonl: added the lines of up-to-date items " << itemList(s.reindexed)
        << " (a run was killed after writing them, before their lines)\n";
  log << "dataset " << manifest.file.filename().string() << ", shard " << shard.index << "/"
      << shard.count << (shardSource.empty() ? "" : " (" + shardSource + ")") << ": " << s.items
      << " of " << manifest.items.size() << " items: " << s.done << " rendered, " << s.skipped
      << " up to date, " << s.failed << " failed" << (s.cancelled ? "; interrupted" : "") << "\n";
  if (s.cancelled) return interrupted();
  return s.failed > 0 ? 1 : 0;
}

}  // namespace camsim
