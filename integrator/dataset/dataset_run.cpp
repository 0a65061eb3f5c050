#include "integrator/dataset/dataset_run.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <exception>
#include <future>
#include <memory>
#include <optional>
#include <set>
#include <thread>
#include <utility>

#include "integrator/capture/capture_run.h"
#include "integrator/capture/capture_writer.h"
#include "integrator/dataset/dataset_item.h"
#include "integrator/dataset/dataset_lock.h"
#include "integrator/dataset/item_writer.h"
#include "sensor/base/fnv1a.h"
#include "sensor/base/input_error.h"
#include "sensor/base/yaml_reader.h"
#include "sensor/io/json_writer.h"
#include "sensor/io/output_set.h"
#include "sensor/isp/color_management.h"

namespace fs = std::filesystem;

namespace camsim {
namespace {

// A temporary item folder's prefix: ".NNNNNN.camsim-tmp-" (the PID follows).
std::string temporaryPrefix(std::size_t index) {
  return "." + itemFolderName(index) + ".camsim-tmp-";
}

// The OCIO config the pictures go through, wherever it was found ($OCIO included), by its
// content: its text and the files of its search_path folders (LUTs, looks), so that another
// config or an edited LUT renders the items again and the same config elsewhere does not
// (found by probing: $OCIO was not in the key, and --resume kept pictures of another config).
std::string ocioConfigKey(const fs::path& explicitConfig) {
  const OcioProcessor ocio(explicitConfig);  // InputError for a config that cannot be read
  std::string key = fnv1aHex(readWholeFile(ocio.location().path));
  const std::vector<fs::path> folders = ocio.searchFolders();
  for (std::size_t i = 0; i < folders.size(); ++i) {
    std::error_code ec;
    std::vector<fs::path> files;
    for (fs::directory_iterator it(folders[i], ec), end; !ec && it != end; it.increment(ec))
      if (it->is_regular_file(ec)) files.push_back(it->path());
    std::sort(files.begin(), files.end());
    for (const fs::path& f : files)  // by the folder's place, not its path: any checkout alike
      key +=
          " " + std::to_string(i) + "/" + f.filename().string() + "=" + fnv1aHex(readWholeFile(f));
  }
  return key;
}

// Removes the temporary folders a killed run left for item `index`: this shard owns the
// item, so whatever process wrote them is gone (or is a second run of the same shard).
std::vector<fs::path> removeTemporaries(const fs::path& items, std::size_t index) {
  std::vector<fs::path> removed;
  std::error_code ec;
  if (!fs::is_directory(items, ec)) return removed;
  const std::string prefix = temporaryPrefix(index);
  for (const auto& entry : fs::directory_iterator(items, ec))
    if (entry.path().filename().string().rfind(prefix, 0) == 0) {
      fs::remove_all(entry.path(), ec);
      removed.push_back(entry.path());
    }
  return removed;
}

// Renders the item into w: a single capture is kept for the writer (w.capture), a
// sequence's frames are written into w.tmp as they finish. False when cancelled.
bool renderItem(SceneDescription desc, ItemWork& w, const DatasetRunOptions& options,
                const std::function<void(double)>& fraction) {
  CaptureOutputOptions out{w.tmp, options.picture, false, true};
  out.datasetItem = static_cast<int>(w.item.index);  // BOP scene, KITTI image (capture_writer.h)
  CaptureOptions co;
  co.threads = options.threads;
  co.cancel = options.cancel;
  co.progress = [&](int done, int total) { fraction(static_cast<double>(done) / total); };
  const bool sequence = desc.frames.has_value();
  // The item's one writer, made before it renders (the pose exports' models with it: a scene
  // whose BOP or KITTI export cannot be written is refused here). It writes a sequence's
  // frames as they arrive; a single capture is kept for writeItem, which overlaps the next
  // item's rendering.
  w.writer.emplace(out, desc);
  const SequenceSummary s = captureScene(std::move(desc), co, [&](CaptureResult&& c, int) {
    if (c.cancelled) return;
    w.renderSeconds += c.stats.seconds;
    if (sequence)
      w.writer->write(c);
    else
      w.capture = std::move(c);
  });
  if (s.cancelled) return false;
  if (sequence) {
    w.writer->finish();
    w.files.insert(w.files.end(), w.writer->files().begin(), w.writer->files().end());
  }
  return true;
}

void count(DatasetRunSummary& s, const ItemReport& r) {
  if (r.status == ItemStatus::kDone) ++s.done;
  if (r.status == ItemStatus::kSkipped) ++s.skipped;
  if (r.status == ItemStatus::kFailed) ++s.failed;
}

// A folder that holds another manifest's dataset is refused before anything is written
// (found by probing: a second manifest's run into the folder left the first's items beside
// its own, and two "item 0 done" lines in the index). The same manifest, by name or by
// content, may run again — edited, with --resume keeping what is up to date — but not over
// item folders past its item count, left by a longer earlier version.
void checkEarlierRun(const Manifest& manifest, const fs::path& directory) {
  const fs::path record = directory / "dataset.json";
  std::error_code ec;
  if (!fs::is_regular_file(record, ec)) return;
  YamlMap earlier(parseYaml(readWholeFile(record), record.string()));
  const auto format = earlier.find("format");
  if (!format || !format->isScalar() || format->string() != "camsim-dataset-output/1")
    (format ? *format : earlier.self())
        .fail(
            "not a camsim dataset folder (its dataset.json is another program's): write the "
            "dataset to another --output folder");
  const YamlValue name = earlier.require("manifest");
  const std::string hash = earlier.require("manifest_fnv1a64").string();
  if (name.string() != manifest.file.filename().string() && hash != fnv1aHex(manifest.text))
    name.fail("this folder holds the dataset of another manifest ('" + name.string() +
              "'); write " + manifest.file.filename().string() +
              "'s elsewhere (another --output) or remove this folder");
  if (!fs::is_directory(directory / "items", ec)) return;
  std::set<std::size_t> surplus;  // in order: the smallest is named
  for (const auto& entry : fs::directory_iterator(directory / "items", ec)) {
    const std::string folder = entry.path().filename().string();
    if (folder.empty() || folder.size() > 18 ||
        folder.find_first_not_of("0123456789") != std::string::npos)
      continue;
    if (const std::size_t index = std::stoull(folder); index >= manifest.items.size())
      surplus.insert(index);
  }
  if (surplus.empty()) return;
  const std::size_t n = manifest.items.size();
  throw InputError(
      {(directory / "items" / itemFolderName(*surplus.begin())).string(), 0, 0}, "",
      "an item this manifest does not have (it has " + std::to_string(n) +
          (n == 1 ? " item" : " items") + "), left by an earlier run" +
          (surplus.size() > 1 ? " with " + std::to_string(surplus.size() - 1) + " more" : "") +
          ": remove them (their index.jsonl lines stay, a log), or write to another --output "
          "folder");
}

}  // namespace

const char* itemStatusName(ItemStatus status) {
  switch (status) {
    case ItemStatus::kDone:
      return "done";
    case ItemStatus::kSkipped:
      return "skipped";
    case ItemStatus::kFailed:
      return "failed";
    case ItemStatus::kInterrupted:
      return "interrupted";
  }
  return "?";
}

DatasetRunSummary runDataset(const Manifest& manifest, const DatasetRunOptions& options) {
  CAMSIM_CHECK(options.shard.count >= 1 && options.shard.index >= 0 &&
               options.shard.index < options.shard.count);
  const std::string outputKey = "ocio=" + ocioConfigKey(options.picture.ocioConfig) +
                                " display=" + options.picture.choice.display +
                                " view=" + options.picture.choice.view +
                                " looks=" + options.picture.choice.looks;
  if (options.onlyItem) {
    if (*options.onlyItem >= manifest.items.size())
      throw InputError({manifest.file.string(), 0, 0}, "",
                       "item " + std::to_string(*options.onlyItem) +
                           " does not exist (the manifest has " +
                           std::to_string(manifest.items.size()) + " items: 0 to " +
                           std::to_string(manifest.items.size() - 1) + ")");
    if (!options.shard.owns(*options.onlyItem))
      throw InputError({manifest.file.string(), 0, 0}, "",
                       "item " + std::to_string(*options.onlyItem) + " is not in shard " +
                           std::to_string(options.shard.index) + "/" +
                           std::to_string(options.shard.count));
  }
  // Every item checked before anything is written or rendered.
  DatasetRunSummary summary;
  if (!checkDataset(manifest,
                    {options.onChecked, options.maxMemoryGb, options.threads, options.cancel})) {
    summary.cancelled = summary.cancelledWhileChecking = true;  // nothing written
    return summary;
  }
  checkEarlierRun(manifest, options.directory);
  std::vector<std::size_t> mine;
  for (const DatasetItem& item : manifest.items)
    if (options.shard.owns(item.index) && (!options.onlyItem || *options.onlyItem == item.index))
      mine.push_back(item.index);

  summary.items = mine.size();
  // This shard's items are this process's from here on (dataset_lock.h): a second run of the
  // shard is refused before it removes or writes anything.
  const DatasetLock lock(options.directory, options.shard.index, options.shard.count);
  if (!lock.warning().empty() && options.onWarning) options.onWarning(lock.warning());
  const fs::path items = options.directory / "items";
  for (const auto& stale : OutputSet::prepareDirectory(options.directory))
    summary.removed.push_back(stale);
  (void)OutputSet::prepareDirectory(items);
  {
    OutputSet record(options.directory);
    record.addText("dataset.json", JsonObject()
                                           .set("format", "camsim-dataset-output/1")
                                           .set("manifest", manifest.file.filename().string())
                                           .set("manifest_fnv1a64", fnv1aHex(manifest.text))
                                           .set("camsim_version", CAMSIM_VERSION)
                                           .setInteger("items", manifest.items.size())
                                           .str() +
                                       "\n");
    record.commit();
  }
  const std::string shardText =
      std::to_string(options.shard.index) + "/" + std::to_string(options.shard.count);
  // With --resume: the index's done lines, read when the first item is up to date, to give
  // an up-to-date item whose run was killed between its rename and its line the line it
  // lacks (once: lines of this shard's items are written by this process only, and each
  // item once per run).
  std::optional<IndexLines> indexed;
  // Item n is written on the writer thread, and item n + 2 loaded, while item n + 1 renders
  // (single captures; a sequence writes its frames as they finish). Reports and progress
  // come from this thread.
  std::thread writerThread;  // writes item n while item n + 1 renders
  std::exception_ptr writerError;
  std::future<ResolvedItem> next;  // item n + 1, loaded while item n renders
  std::optional<ItemReport> written;
  std::size_t finished = 0;
  auto collect = [&]() {
    if (!writerThread.joinable()) return;
    writerThread.join();
    if (writerError) std::rethrow_exception(std::exchange(writerError, nullptr));
    count(summary, *written);
    if (options.onItem) options.onItem(*written);
    ++finished;
    if (options.progress) options.progress(finished, mine.size(), 0.0);
  };
  struct JoinOnExit {  // an exception in this thread: the writer finishes first
    std::thread& t;
    ~JoinOnExit() {
      if (t.joinable()) t.join();
    }
  } joinOnExit{writerThread};
  struct WaitOnExit {  // nor may the loading of the next item outlive this call
    std::future<ResolvedItem>& f;
    ~WaitOnExit() {
      if (f.valid()) f.wait();
    }
  } waitOnExit{next};
  for (std::size_t n = 0; n < mine.size(); ++n) {
    const std::size_t index = mine[n];
    if (options.cancel && options.cancel->load()) {
      summary.cancelled = true;
      break;
    }
    for (auto& t : removeTemporaries(items, index)) summary.removed.push_back(t);
    auto work = std::make_shared<ItemWork>();
    // Loaded while the previous item rendered (the first: now).
    work->item = n == 0 ? resolveItem(manifest, manifest.items[index], outputKey) : next.get();
    if (n + 1 < mine.size())
      next = std::async(std::launch::async, [&manifest, &outputKey, i = mine[n + 1]] {
        return resolveItem(manifest, manifest.items[i], outputKey);
      });
    work->finalDir = items / itemFolderName(index);
    work->indexFile = options.directory / "index.jsonl";
    work->shard = shardText;
    work->picture = options.picture;
    work->start = std::chrono::steady_clock::now();
    std::vector<JsonObject> files;
    if (options.resume && itemUpToDate(work->finalDir, work->item.hash, &files)) {
      collect();  // the previous item's line first: lines in item order
      if (!indexed) indexed = readIndex(options.directory / "index.jsonl");
      if (!indexed->done.count({index, work->item.hash})) {
        reindexItem(*work, files);
        summary.reindexed.push_back(index);
      }
      ItemReport skipped;
      skipped.index = index;
      skipped.status = ItemStatus::kSkipped;
      count(summary, skipped);
      if (options.onItem) options.onItem(skipped);
      ++finished;
      if (options.progress) options.progress(finished, mine.size(), 0.0);
      continue;
    }
    work->tmp = items / (temporaryPrefix(index) + std::to_string(::getpid()));
    fs::create_directories(work->tmp);
    bool rendered = false;
    try {
      rendered = renderItem(work->item.description, *work, options, [&](double f) {
        if (options.progress) options.progress(finished, mine.size(), f);
      });
    } catch (const InputError& e) {  // found while rendering (white balance, metering…)
      std::error_code ec;
      fs::remove_all(work->tmp, ec);
      throw work->item.manifestError(e);
    } catch (const std::exception& e) {
      work->capture.reset();
      work->writer.reset();
      work->files.clear();
      work->renderSeconds = 0.0;
      collect();
      ItemReport failed = recordFailure(*work, e.what());
      count(summary, failed);
      if (options.onItem) options.onItem(failed);
      ++finished;
      continue;
    }
    if (!rendered) {
      std::error_code ec;
      fs::remove_all(work->tmp, ec);
      collect();
      ItemReport interrupted;
      interrupted.index = index;
      interrupted.status = ItemStatus::kInterrupted;
      summary.cancelled = true;
      if (options.onItem) options.onItem(interrupted);
      break;
    }
    collect();  // the previous item's files are complete before this one's are written
    writerThread = std::thread([&manifest, work, &written, &writerError] {
      try {
        written = writeItem(manifest, *work);
      } catch (...) {
        writerError = std::current_exception();
      }
    });
    if (work->item.description.frames) collect();  // a sequence: nothing to overlap
  }
  collect();
  return summary;
}

DatasetStatus datasetStatus(const fs::path& directory) {
  const fs::path record = directory / "dataset.json";
  std::error_code ec;
  if (!fs::is_regular_file(record, ec))
    throw InputError({directory.string(), 0, 0}, "",
                     "not a camsim dataset folder (no dataset.json: nothing has run into it)");
  DatasetStatus s;
  // The record as runDataset writes it (found by probing: an edited "items" of 10^8 kept
  // --status counting, past SIGTERM, and 9e18 grew its list of missing items without end).
  YamlMap map(parseYaml(readWholeFile(record), record.string()));
  const YamlValue format = map.require("format");
  if (format.string() != "camsim-dataset-output/1")
    format.fail("not a camsim dataset record (camsim-dataset-output/1)");
  s.total = static_cast<std::size_t>(
      map.require("items").integer(0, static_cast<std::int64_t>(kMaxDatasetItems)));
  const IndexLines index = readIndex(directory / "index.jsonl");
  std::set<std::size_t> listed;  // items with a done line
  for (const auto& [item, hash] : index.done) listed.insert(item);
  for (std::size_t i = 0; i < s.total; ++i) {
    if (fs::is_regular_file(directory / "items" / itemFolderName(i) / "item.json", ec)) {
      ++s.done;
      if (!listed.count(i)) s.unindexedItems.push_back(i);
    } else if (index.failed.count(i)) {
      ++s.failed;
      s.failedItems.push_back(i);
    } else {
      ++s.missing;
      s.missingItems.push_back(i);
    }
  }
  if (fs::is_directory(directory / "items", ec))
    for (const auto& entry : fs::directory_iterator(directory / "items", ec))
      if (entry.path().filename().string().find(".camsim-tmp-") != std::string::npos)
        ++s.temporaries;
  return s;
}

}  // namespace camsim
