#include "integrator/dataset/item_writer.h"

#include <fcntl.h>
#include <unistd.h>

#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "sensor/base/fnv1a.h"
#include "sensor/base/input_error.h"
#include "sensor/base/yaml_reader.h"
#include "sensor/io/json_writer.h"
#include "sensor/io/output_set.h"

namespace fs = std::filesystem;

namespace camsim {
namespace {

// Length of the JSON number (RFC 8259 grammar) at text[i], or 0 if none starts there.
size_t jsonNumberLength(const std::string& text, size_t i) {
  const size_t start = i;
  auto digits = [&] {
    const size_t from = i;
    while (i < text.size() && text[i] >= '0' && text[i] <= '9') ++i;
    return i - from;
  };
  if (i < text.size() && text[i] == '-') ++i;
  if (i < text.size() && text[i] == '0') {
    ++i;
  } else if (digits() == 0) {
    return 0;
  }
  if (i < text.size() && text[i] == '.') {
    ++i;
    if (digits() == 0) return 0;
  }
  if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
    if (digits() == 0) return 0;
  }
  return i - start;
}

// True if yaml is one JSON number or a flow list "[n, n, ...]" of them.
bool isJsonNumberOrList(const std::string& yaml) {
  if (const size_t n = jsonNumberLength(yaml, 0); n > 0) return n == yaml.size();
  if (yaml.size() < 2 || yaml.front() != '[' || yaml.back() != ']') return false;
  size_t i = 1;
  const size_t end = yaml.size() - 1;
  auto spaces = [&] {
    while (i < end && yaml[i] == ' ') ++i;
  };
  spaces();
  while (i < end) {
    const size_t n = jsonNumberLength(yaml, i);
    if (n == 0 || i + n > end) return false;
    i += n;
    spaces();
    if (i == end) break;
    if (yaml[i] != ',') return false;
    ++i;
    spaces();
    if (i == end) return false;  // a trailing comma is not JSON
  }
  return true;
}

JsonObject parametersJson(const ResolvedItem& item) {
  JsonObject p;
  for (const auto& [path, value] : item.parameters) p.setJson(path, parameterJson(value));
  return p;
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

}  // namespace

std::string parameterJson(const std::string& yaml) {
  if (yaml == "~" || yaml == "null") return "null";
  return isJsonNumberOrList(yaml) ? yaml : JsonObject::quoted(yaml);
}

std::string readWholeFile(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

bool itemUpToDate(const fs::path& dir, const std::string& hash, std::vector<JsonObject>* files) {
  const fs::path record = dir / "item.json";
  std::error_code ec;
  if (!fs::is_regular_file(record, ec)) return false;
  try {
    YamlMap j(parseYaml(readWholeFile(record), record.string()));
    if (j.require("hash").string() != hash || j.require("status").string() != "done") return false;
    for (const YamlValue& f : j.require("files").items()) {
      YamlMap file(f);
      const std::string path = file.require("path").string();
      if (!fs::is_regular_file(dir / path, ec)) return false;
      if (files)
        files->push_back(
            JsonObject().set("path", path).set("fnv1a64", file.require("fnv1a64").string()));
    }
    return true;
  } catch (const InputError&) {
    return false;  // unreadable: render again
  }
}

IndexLines readIndex(const fs::path& indexFile) {
  IndexLines lines;
  std::ifstream in(indexFile);
  for (std::string text; std::getline(in, text);) {
    if (text.empty()) continue;
    try {
      YamlMap j(parseYaml(text, indexFile.string()));
      const auto item = static_cast<std::size_t>(j.require("item").integer(0, INT64_MAX));
      const std::string status = j.require("status").string();
      if (status == "done") lines.done.emplace(item, j.require("hash").string());
      if (status == "failed") lines.failed.insert(item);
    } catch (const InputError&) {
      // a line cut by a killed writer: not counted
    }
  }
  return lines;
}

namespace {

void appendItemLine(const ItemWork& w, const ItemReport& report, JsonObject line) {
  line.set("seconds", report.seconds)
      .set("render_seconds", report.renderSeconds)
      .set("shard", w.shard)
      .set("parameters", parametersJson(w.item));
  appendLine(w.indexFile, line.line());
}

double secondsSince(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// The fault-injection point between an item's rename and its index line, for the test that
// a kill there loses nothing (tests/cli/dataset_command_test.cpp): with
// CAMSIM_TEST_KILL_AFTER_RENAME=N in the environment, item N's writer raises SIGKILL here.
void killPointAfterRename(std::size_t index) {
  const char* item = std::getenv("CAMSIM_TEST_KILL_AFTER_RENAME");
  if (item && *item && std::to_string(index) == item) std::raise(SIGKILL);
}

}  // namespace

void reindexItem(const ItemWork& w, const std::vector<JsonObject>& files) {
  JsonObject line;
  line.setInteger("item", w.item.index)
      .set("status", "done")
      .set("hash", w.item.hash)
      .set("files", files)
      .setJson("seconds", "null")
      .setJson("render_seconds", "null")
      .set("shard", w.shard)
      .set("parameters", parametersJson(w.item));
  appendLine(w.indexFile, line.line());
}

ItemReport recordFailure(ItemWork& w, const std::string& why) {
  std::error_code ec;
  fs::remove_all(w.tmp, ec);
  ItemReport r;
  r.index = w.item.index;
  r.status = ItemStatus::kFailed;
  r.message = why;
  r.seconds = secondsSince(w.start);
  JsonObject line;
  line.setInteger("item", r.index).set("status", "failed").set("error", why);
  appendItemLine(w, r, line);
  return r;
}

ItemReport writeItem(const Manifest& manifest, ItemWork& w) {
  const std::size_t index = w.item.index;
  ItemReport report;
  report.index = index;
  report.renderSeconds = w.renderSeconds;
  JsonObject line;
  line.setInteger("item", index);
  std::error_code ec;
  try {
    if (w.capture) {
      for (auto& f : w.writer->write(*w.capture).files) w.files.push_back(f);
      w.writer->finish();  // a single capture: nothing more (capture_run.h)
      w.capture.reset();
    }
    OutputSet extra(w.tmp);
    extra.addText("scene.yaml", "# camsim dataset " + manifest.file.filename().string() +
                                    ", item " + std::to_string(index) + ": the base scene " +
                                    manifest.scene.filename().string() +
                                    " with the item's values; its relative paths resolve "
                                    "against the base scene's folder\n" +
                                    w.item.sceneText);
    extra.addText(
        "params.json",
        JsonObject().setInteger("item", index).set("parameters", parametersJson(w.item)).str() +
            "\n");
    for (auto& f : extra.commit()) w.files.push_back(f);
    // Each file by its path in the item folder (colmap/…, bop/…: in subfolders).
    std::vector<JsonObject> files;
    for (const fs::path& f : w.files) {
      const fs::path inItem = f.lexically_relative(w.tmp);
      files.push_back(JsonObject()
                          .set("path", inItem.generic_string())
                          .set("fnv1a64", fnv1aHex(readWholeFile(w.tmp / inItem))));
    }
    OutputSet last(w.tmp);
    last.addText("item.json", JsonObject()
                                      .setInteger("item", index)
                                      .set("status", "done")
                                      .set("hash", w.item.hash)
                                      .set("camsim_version", CAMSIM_VERSION)
                                      .set("files", files)
                                      .str() +
                                  "\n");
    last.commit();
    fs::remove_all(w.finalDir, ec);  // an older version of the item
    fs::rename(w.tmp, w.finalDir);
    killPointAfterRename(index);
    report.status = ItemStatus::kDone;
    report.files = files.size();
    line.set("status", "done").set("hash", w.item.hash).set("files", files);
  } catch (const InputError&) {
    fs::remove_all(w.tmp, ec);
    throw;  // bad input (an unwritable folder): the run stops with exit 2
  } catch (const std::exception& e) {
    fs::remove_all(w.tmp, ec);
    report.status = ItemStatus::kFailed;
    report.message = e.what();
    line.set("status", "failed").set("error", std::string(e.what()));
  }
  report.seconds = secondsSince(w.start);
  appendItemLine(w, report, line);
  return report;
}

}  // namespace camsim
