#include "integrator/dataset/dataset_run.h"

#include <fcntl.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "integrator/capture/capture.h"
#include "integrator/capture/capture_writer.h"
#include "integrator/capture/dataset_writer.h"
#include "integrator/dataset/dataset_item.h"
#include "sensor/base/fnv1a.h"
#include "sensor/base/input_error.h"
#include "sensor/base/yaml_reader.h"
#include "sensor/io/json_writer.h"
#include "sensor/io/output_set.h"

namespace fs = std::filesystem;

namespace camsim {
namespace {

std::string readAll(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// A temporary item folder's prefix: ".NNNNNN.camsim-tmp-" (the PID follows).
std::string temporaryPrefix(std::size_t index) {
  return "." + itemFolderName(index) + ".camsim-tmp-";
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

// A parameter value as JSON: a number as written when it is a JSON number, anything else
// (a list, a name) as its YAML text in a string.
std::string jsonValue(const std::string& yaml) {
  static const std::regex number(R"(-?(0|[1-9][0-9]*)(\.[0-9]+)?([eE][-+]?[0-9]+)?)");
  static const std::regex numbers(
      R"(\[ *(-?(0|[1-9][0-9]*)(\.[0-9]+)?([eE][-+]?[0-9]+)?( *, *)?)* *\])");
  if (yaml == "~" || yaml == "null") return "null";
  return std::regex_match(yaml, number) || std::regex_match(yaml, numbers)
             ? yaml
             : JsonObject::quoted(yaml);
}

JsonObject parametersJson(const ResolvedItem& item) {
  JsonObject p;
  for (const auto& [path, value] : item.parameters) p.setJson(path, jsonValue(value));
  return p;
}

// Whether the item's recorded outputs are still its outputs: item.json's hash and files.
bool upToDate(const fs::path& dir, const std::string& hash) {
  const fs::path record = dir / "item.json";
  std::error_code ec;
  if (!fs::is_regular_file(record, ec)) return false;
  try {
    YamlMap j(parseYaml(readAll(record), record.string()));
    if (j.require("hash").string() != hash || j.require("status").string() != "done") return false;
    for (const YamlValue& f : j.require("files").items())
      if (!fs::is_regular_file(dir / YamlMap(f).require("path").string(), ec)) return false;
    return true;
  } catch (const InputError&) {
    return false;  // unreadable: render again
  }
}

// One line appended with a single write(2) on an O_APPEND descriptor: lines of processes
// writing at once do not interleave (a local or NFS-with-locking file system).
void appendLine(const fs::path& file, const std::string& line) {
  const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd < 0) throw InputError({file.string(), 0, 0}, "", "cannot open the dataset index");
  const std::string text = line + "\n";
  const ssize_t n = ::write(fd, text.data(), text.size());
  ::close(fd);
  if (n != static_cast<ssize_t>(text.size()))
    throw InputError({file.string(), 0, 0}, "", "cannot append to the dataset index");
}

struct Rendered {
  std::vector<fs::path> files;
  bool cancelled = false;
  double renderSeconds = 0.0;  // in render(): the rest of the item's time is overhead
};

// The item's capture or sequence, written into `dir` (reproducible bytes).
Rendered renderItem(SceneDescription desc, const fs::path& dir, const DatasetRunOptions& options,
                    const std::function<void(double)>& fraction) {
  CaptureOutputOptions out{dir, options.picture, false, true};
  CaptureOptions co;
  co.threads = options.threads;
  co.cancel = options.cancel;
  Rendered r;
  if (!desc.frames) {
    co.progress = [&](int done, int total) { fraction(static_cast<double>(done) / total); };
    const CaptureResult result = capture(std::move(desc), co);
    if (result.cancelled) return {{}, true, 0.0};
    r.files = writeCapture(result, out).files;
    r.renderSeconds = result.stats.seconds;
    return r;
  }
  const int count = desc.frames->count;
  int frame = 0;
  co.progress = [&](int done, int total) {
    fraction((frame + static_cast<double>(done) / total) / count);
  };
  std::vector<DatasetFrame> frames;
  const SequenceSummary s = captureSequence(std::move(desc), co, [&](CaptureResult&& c, int k) {
    frame = k + 1;
    if (c.cancelled) return;
    r.renderSeconds += c.stats.seconds;
    for (auto& f : writeCapture(c, out).files) r.files.push_back(f);
    frames.push_back(datasetFrame(c));
  });
  if (s.cancelled) return {{}, true, 0.0};
  for (auto& f : writeDatasetMetadata(frames, dir)) r.files.push_back(f);
  return r;
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
  CAMSIM_CHECK(options.shard.count >= 1 && options.shard.index < options.shard.count);
  const std::string outputKey =
      "ocio=" + options.picture.ocioConfig.string() + " display=" + options.picture.choice.display +
      " view=" + options.picture.choice.view + " looks=" + options.picture.choice.looks;
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
  checkBaseScene(manifest);
  for (const DatasetItem& item : manifest.items) {
    (void)resolveItem(manifest, item, outputKey);
    if (options.onChecked) options.onChecked(item.index + 1, manifest.items.size());
  }
  std::vector<std::size_t> mine;
  for (const DatasetItem& item : manifest.items)
    if (options.shard.owns(item.index) && (!options.onlyItem || *options.onlyItem == item.index))
      mine.push_back(item.index);

  DatasetRunSummary summary;
  summary.items = mine.size();
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
  for (std::size_t n = 0; n < mine.size(); ++n) {
    const std::size_t index = mine[n];
    if (options.cancel && options.cancel->load()) {
      summary.cancelled = true;
      break;
    }
    for (auto& t : removeTemporaries(items, index)) summary.removed.push_back(t);
    const ResolvedItem item = resolveItem(manifest, manifest.items[index], outputKey);
    const fs::path finalDir = items / itemFolderName(index);
    ItemReport report;
    report.index = index;
    if (options.resume && upToDate(finalDir, item.hash)) {
      report.status = ItemStatus::kSkipped;
      ++summary.skipped;
      if (options.onItem) options.onItem(report);
      if (options.progress) options.progress(n + 1, mine.size(), 0.0);
      continue;
    }
    const auto start = std::chrono::steady_clock::now();
    const fs::path tmp = items / (temporaryPrefix(index) + std::to_string(::getpid()));
    fs::create_directories(tmp);
    struct RemoveOnExit {  // an exception or a cancel leaves no temporary behind
      fs::path dir;
      ~RemoveOnExit() {
        std::error_code ec;
        if (!dir.empty()) fs::remove_all(dir, ec);
      }
    } cleanup{tmp};
    JsonObject line;
    line.setInteger("item", index);
    try {
      Rendered r = renderItem(item.description, tmp, options, [&](double f) {
        if (options.progress) options.progress(n, mine.size(), f);
      });
      if (r.cancelled) {
        report.status = ItemStatus::kInterrupted;
        summary.cancelled = true;
        if (options.onItem) options.onItem(report);
        break;
      }
      OutputSet extra(tmp);
      extra.addText("scene.yaml", "# camsim dataset " + manifest.file.filename().string() +
                                      ", item " + std::to_string(index) + ": the base scene " +
                                      manifest.scene.filename().string() +
                                      " with the item's values; its relative paths resolve "
                                      "against the base scene's folder\n" +
                                      item.sceneText);
      extra.addText(
          "params.json",
          JsonObject().setInteger("item", index).set("parameters", parametersJson(item)).str() +
              "\n");
      for (auto& f : extra.commit()) r.files.push_back(f);
      std::vector<JsonObject> files;
      for (const fs::path& f : r.files)
        files.push_back(JsonObject()
                            .set("path", f.filename().string())
                            .set("fnv1a64", fnv1aHex(readAll(tmp / f.filename()))));
      report.seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      report.files = files.size();
      report.renderSeconds = r.renderSeconds;
      OutputSet last(tmp);
      last.addText("item.json", JsonObject()
                                        .setInteger("item", index)
                                        .set("status", "done")
                                        .set("hash", item.hash)
                                        .set("camsim_version", CAMSIM_VERSION)
                                        .set("files", files)
                                        .str() +
                                    "\n");
      last.commit();
      std::error_code ec;
      fs::remove_all(finalDir, ec);  // an older version of the item
      fs::rename(tmp, finalDir);
      cleanup.dir.clear();
      report.status = ItemStatus::kDone;
      ++summary.done;
      line.set("status", "done").set("hash", item.hash).set("files", files);
    } catch (const InputError&) {
      throw;  // bad input: the whole run stops (exit 2), the temporary is removed
    } catch (const std::exception& e) {
      report.status = ItemStatus::kFailed;
      report.message = e.what();
      ++summary.failed;
      line.set("status", "failed").set("error", std::string(e.what()));
    }
    line.set("seconds", report.seconds)
        .set("render_seconds", report.renderSeconds)
        .set("shard", shardText)
        .set("parameters", parametersJson(item));
    appendLine(options.directory / "index.jsonl", line.line());
    if (options.onItem) options.onItem(report);
    if (options.progress) options.progress(n + 1, mine.size(), 0.0);
  }
  return summary;
}

DatasetStatus datasetStatus(const fs::path& directory) {
  const fs::path record = directory / "dataset.json";
  std::error_code ec;
  if (!fs::is_regular_file(record, ec))
    throw InputError({directory.string(), 0, 0}, "",
                     "not a camsim dataset folder (no dataset.json: nothing has run into it)");
  DatasetStatus s;
  s.total = static_cast<std::size_t>(
      YamlMap(parseYaml(readAll(record), record.string())).require("items").integer(0, INT64_MAX));
  std::set<std::size_t> failed;
  std::ifstream index(directory / "index.jsonl");
  for (std::string text; std::getline(index, text);) {
    if (text.empty()) continue;
    try {
      YamlMap j(parseYaml(text, (directory / "index.jsonl").string()));
      if (j.require("status").string() == "failed")
        failed.insert(static_cast<std::size_t>(j.require("item").integer(0, INT64_MAX)));
    } catch (const InputError&) {
      // a line cut by a killed writer: not counted
    }
  }
  for (std::size_t i = 0; i < s.total; ++i) {
    if (fs::is_regular_file(directory / "items" / itemFolderName(i) / "item.json", ec)) {
      ++s.done;
    } else if (failed.count(i)) {
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
