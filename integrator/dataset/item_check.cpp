// checkDataset (item_check.h): every item resolved, loaded and its pose exports' models made
// on all cores, and the items' BOP models compared with the first item's.
#include "integrator/dataset/item_check.h"

#include <atomic>
#include <cstdint>
#include <exception>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <tbb/parallel_for.h>

#include "integrator/capture/bop_writer.h"
#include "integrator/capture/resource_guard.h"
#include "integrator/dataset/dataset_item.h"
#include "sensor/base/format.h"
#include "sensor/base/input_error.h"

namespace camsim {
namespace {

// An item, resolved, with its pose exports' models (empty without `exports: [bop]` or
// `[kitti]`). An error the models find is reported at the manifest line that set its key, as
// the loader's are (found by probing: BOP's model check named a line of the edited scene
// text).
struct ItemModels {
  ResolvedItem item;
  PoseModels models;
};

// With its memory held to the limit (found by probing: a 32768 × 8192 item passed --check
// and then failed with std::bad_alloc, exit 1).
ItemModels itemModels(const Manifest& manifest, std::size_t index,
                      std::optional<double> maxMemoryGb) {
  ItemModels m{resolveItem(manifest, manifest.items[index], ""), {}};
  try {
    checkMemoryLimit(m.item.description, maxMemoryGb);
    m.models = PoseModels(m.item.description);
  } catch (const InputError& e) {
    throw m.item.manifestError(e);
  }
  return m;
}

// InputError (the item's) when one of item's BOP models differs from reference's model of
// the same obj_id. Found by probing: a grid over a labelled mesh's `scale` wrote
// obj_000002.ply 159 mm across in item 0 and 238 mm in item 1, so the gathered dataset posed
// one of them against the other's model.
void checkSameModels(const ItemModels& reference, const ItemModels& item) {
  const DifferentBopModels d = firstDifferentBopModels(reference.models.bop(), item.models.bop());
  if (!d.other) return;
  const SceneDescription& s = item.item.description;
  // No key: the item's values (not `exports`, which a manifest's `set` may name) made it.
  throw item.item.manifestError(InputError(
      exportsPlace(s), "",
      "bop: shape '" + s.shapes[d.other->shape].label + "' has class " +
          std::to_string(d.other->objId) + " (BOP's obj_id) but a different model than shape '" +
          reference.item.description.shapes[d.reference->shape].label + "' of item " +
          std::to_string(reference.item.index) +
          ": the items of a dataset are one BOP dataset, with one model per obj_id (models/obj_" +
          formatSixDigits(d.other->objId) +
          ".ply): vary a class's pose, not its mesh or scale, or give each variant a class of "
          "its own (docs/dataset-format.md)"));
}

// The obj_ids of models that reference lacks.
std::vector<std::uint32_t> idsMissingFrom(const PoseModels& reference, const PoseModels& models) {
  std::vector<std::uint32_t> ids;
  for (const BopModel& m : models.bop()) {
    bool found = false;
    for (const BopModel& r : reference.bop()) found = found || r.objId == m.objId;
    if (!found) ids.push_back(m.objId);
  }
  return ids;
}

void rethrowFirst(const std::vector<std::exception_ptr>& errors) {
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
}

// Every item's models against the first item's, on all cores; the models are dropped as they
// are checked (all items' at once would hold every scene), the first item's kept. An obj_id
// the first item lacks is then checked against the first item that has it, one item at a
// time (rare: a manifest that adds a class in later items).
void checkItems(const Manifest& manifest,
                const std::function<void(std::size_t, std::size_t)>& onChecked,
                std::optional<double> maxMemoryGb) {
  const std::size_t n = manifest.items.size();
  if (n == 0) return;
  std::vector<std::exception_ptr> errors(n);
  std::vector<std::vector<std::uint32_t>> newIds(n);  // per item: obj_ids item 0 lacks
  std::optional<ItemModels> first;
  try {
    first.emplace(itemModels(manifest, 0, maxMemoryGb));
  } catch (...) {
    errors[0] = std::current_exception();
  }
  std::atomic<std::size_t> done{0};
  std::mutex progress;
  tbb::parallel_for(std::size_t{0}, n, [&](std::size_t i) {
    if (i > 0) try {
        const ItemModels m = itemModels(manifest, i, maxMemoryGb);
        if (first) {
          checkSameModels(*first, m);
          newIds[i] = idsMissingFrom(first->models, m.models);
        }
      } catch (...) {
        errors[i] = std::current_exception();
      }
    const std::size_t d = ++done;
    if (onChecked) {
      std::lock_guard<std::mutex> lock(progress);
      onChecked(d, n);
    }
  });
  rethrowFirst(errors);

  std::map<std::uint32_t, std::size_t> referenceOf;  // obj_id → the first item with it
  for (std::size_t i = 0; i < n; ++i)
    for (const std::uint32_t id : newIds[i]) referenceOf.try_emplace(id, i);
  std::map<std::size_t, ItemModels> references;
  for (const auto& [id, i] : referenceOf)
    if (!references.contains(i)) references.emplace(i, itemModels(manifest, i, maxMemoryGb));
  for (std::size_t i = 0; i < n; ++i) {
    if (newIds[i].empty()) continue;
    std::optional<ItemModels> made;
    const ItemModels& m = references.contains(i)
                              ? references.at(i)
                              : made.emplace(itemModels(manifest, i, maxMemoryGb));
    for (const std::uint32_t id : newIds[i])
      if (referenceOf[id] != i) checkSameModels(references.at(referenceOf[id]), m);
  }
}

}  // namespace

void checkDataset(const Manifest& manifest,
                  const std::function<void(std::size_t, std::size_t)>& onChecked,
                  std::optional<double> maxMemoryGb) {
  checkBaseScene(manifest);
  checkItems(manifest, onChecked, maxMemoryGb);
}

}  // namespace camsim
