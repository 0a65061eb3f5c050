// Writing one rendered dataset item (the layout of dataset_run.h): the capture's files,
// scene.yaml, params.json and item.json (last) into the item's temporary folder, then the
// folder renamed into place and the item's line appended to index.jsonl. runDataset runs it
// on a writer thread of its own for single captures, so that item n is written while item
// n + 1 renders.
//
// The rename and the line are two steps: a process killed between them leaves an item in
// place that the index does not list. `--resume` repairs that (runDataset: an up-to-date item
// without a done line of its hash gets the line, rebuilt by reindexItem), so the pair is
// atomic for every run that resumes. CAMSIM_TEST_KILL_AFTER_RENAME=N (a fault-injection point
// for tests) SIGKILLs the process right between the two steps of item N.
#pragma once

#include <chrono>
#include <cstddef>
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "integrator/capture/capture.h"
#include "integrator/capture/capture_run.h"
#include "integrator/dataset/dataset_item.h"
#include "integrator/dataset/dataset_run.h"
#include "sensor/io/json_writer.h"

namespace camsim {

struct ItemWork {
  ResolvedItem item;
  std::optional<CaptureResult> capture;  // a single capture, still to write
  // The item's files' writer, made before it renders (its pose exports' models with it:
  // capture_run.h); a sequence's frames written as they arrive, a single capture by writeItem.
  std::optional<CaptureRunWriter> writer;
  std::vector<std::filesystem::path> files;  // already written (a sequence's frames)
  double renderSeconds = 0.0;
  std::filesystem::path tmp, finalDir, indexFile;
  std::string shard;  // "i/N", for the index
  PictureSettings picture;
  std::chrono::steady_clock::time_point start;
};

// Done, or failed (an exception inside camsim: recorded in the index, the temporary
// removed). An InputError (a file that cannot be written) is rethrown after the cleanup.
ItemReport writeItem(const Manifest& manifest, ItemWork& work);

// An item that failed while rendering (an exception inside camsim): its temporary removed,
// its index line appended.
ItemReport recordFailure(ItemWork& work, const std::string& why);

// Whether dir holds the item's outputs: item.json with this hash, every listed file present.
// files (if given): item.json's file list ({path, fnv1a64} each), as the index line has it.
bool itemUpToDate(const std::filesystem::path& dir, const std::string& hash,
                  std::vector<JsonObject>* files = nullptr);

// What index.jsonl says: the (item, hash) pairs of its done lines and the items of its
// failed lines. Lines that do not parse (cut by a kill) are left out.
struct IndexLines {
  std::set<std::pair<std::size_t, std::string>> done;
  std::set<std::size_t> failed;
};
IndexLines readIndex(const std::filesystem::path& indexFile);

// Appends the done line of an item that is in place but missing from the index (its run was
// killed between the rename and the line): item, status, hash, files and parameters as
// writeItem writes them, from item.json's files; seconds and render_seconds null (not kept).
void reindexItem(const ItemWork& work, const std::vector<JsonObject>& files);

// A parameter value (its YAML flow text) as the JSON of params.json and index.jsonl: a
// number or a flow list of numbers as written, "~" and "null" as null, anything else (a
// name, a nested list, a map) as a JSON string of the YAML text.
std::string parameterJson(const std::string& yaml);

// The whole file (empty if unreadable).
std::string readWholeFile(const std::filesystem::path& file);

}  // namespace camsim
