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
#include <tbb/task_arena.h>

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

// Why two models of one obj_id are refused. Found by probing: a grid over a labelled mesh's
// `scale` wrote obj_000002.ply 159 mm across in item 0 and 238 mm in item 1, so the gathered
// dataset posed one of them against the other's model.
std::string clash(std::uint32_t objId, const std::string& shape, const std::string& firstShape,
                  std::size_t firstItem) {
  return "bop: shape '" + shape + "' has class " + std::to_string(objId) +
         " (BOP's obj_id) but a different model than shape '" + firstShape + "' of item " +
         std::to_string(firstItem) +
         ": the items of a dataset are one BOP dataset, with one model per obj_id (models/obj_" +
         formatSixDigits(objId) +
         ".ply): vary a class's pose, not its mesh or scale, or give each variant a class of "
         "its own (docs/dataset-format.md)";
}

// The item's error for a message about its models (no key: the item's values made it, not
// `exports`, which a manifest's `set` may name).
InputError modelError(const ItemModels& m, const std::string& message) {
  return m.item.manifestError(InputError(exportsPlace(m.item.description), "", message));
}

// InputError (the item's) when one of item's BOP models differs from first's model of the
// same obj_id.
void checkSameModels(const ItemModels& first, const ItemModels& item) {
  const DifferentBopModels d = firstDifferentBopModels(first.models.bop(), item.models.bop());
  if (!d.other) return;
  throw modelError(
      item, clash(d.other->objId, item.item.description.shapes[d.other->shape].label,
                  first.item.description.shapes[d.reference->shape].label, first.item.index));
}

// A model of an obj_id the first item lacks, kept (not its item's scene) to compare with the
// other items' models of it.
struct KeptModel {
  std::size_t item = 0;
  std::vector<BopModel> model;  // one: the shape firstDifferentBopModels takes
  std::string shape;            // its shape's label
  SourceLocation where;         // the item's error's place and prefix (modelError)
  std::string key, prefix;
};

// item's models of obj_ids that first lacks.
std::vector<KeptModel> modelsMissingFrom(const PoseModels& first, const ItemModels& item) {
  std::vector<KeptModel> kept;
  for (const BopModel& m : item.models.bop()) {
    bool found = false;
    for (const BopModel& r : first.bop()) found = found || r.objId == m.objId;
    if (found) continue;
    const InputError e = modelError(item, "");
    kept.push_back({item.item.index,
                    {m},
                    item.item.description.shapes[m.shape].label,
                    e.where(),
                    e.key(),
                    e.message()});
  }
  return kept;
}

void rethrowFirst(const std::vector<std::exception_ptr>& errors) {
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
}

// Every item's models against the first item's, on all cores; the models are dropped as they
// are checked (all items' at once would hold every scene), the first item's kept. Then the
// models of obj_ids the first item lacks (only those models are kept), each against the first
// item that has it: those clashes are reported after every other error.
bool checkItems(const Manifest& manifest, const DatasetCheckOptions& options) {
  const std::size_t n = manifest.items.size();
  if (n == 0) return true;
  const auto cancelled = [&] { return options.cancel && options.cancel->load(); };
  std::vector<std::exception_ptr> errors(n);
  std::vector<std::vector<KeptModel>> kept(n);  // per item: its models of obj_ids item 0 lacks
  std::optional<ItemModels> first;
  try {
    first.emplace(itemModels(manifest, 0, options.maxMemoryGb));
  } catch (...) {
    errors[0] = std::current_exception();
  }
  std::atomic<std::size_t> done{0};
  std::mutex progress;
  tbb::task_arena arena(options.threads > 0 ? options.threads
                                            : tbb::this_task_arena::max_concurrency());
  arena.execute([&] {
    tbb::parallel_for(std::size_t{0}, n, [&](std::size_t i) {
      if (cancelled()) return;
      if (i > 0) try {
          const ItemModels m = itemModels(manifest, i, options.maxMemoryGb);
          if (first) {
            checkSameModels(*first, m);
            kept[i] = modelsMissingFrom(first->models, m);
          }
        } catch (...) {
          errors[i] = std::current_exception();
        }
      const std::size_t d = ++done;
      if (options.onChecked) {
        std::lock_guard<std::mutex> lock(progress);
        options.onChecked(d, n);
      }
    });
  });
  if (cancelled()) return false;
  rethrowFirst(errors);

  std::map<std::uint32_t, const KeptModel*> firstOf;  // obj_id → the first item's model of it
  for (std::size_t i = 0; i < n; ++i)
    for (const KeptModel& k : kept[i]) {
      const auto [it, added] = firstOf.try_emplace(k.model.front().objId, &k);
      if (added) continue;
      const KeptModel& f = *it->second;
      if (firstDifferentBopModels(f.model, k.model).other)
        throw InputError(k.where, k.key,
                         k.prefix + clash(k.model.front().objId, k.shape, f.shape, f.item));
    }
  return true;
}

}  // namespace

bool checkDataset(const Manifest& manifest, const DatasetCheckOptions& options) {
  checkBaseScene(manifest);
  return checkItems(manifest, options);
}

}  // namespace camsim
