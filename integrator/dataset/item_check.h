// Checking a dataset's items before anything is written or rendered (runDataset, `camsim
// dataset --check`): the base scene, then every item resolved and loaded (on all cores) with
// its pose exports' models made, and with `exports: [bop]` one model per obj_id across the
// items — their train_pbr/ scenes gather into one BOP dataset under one models/
// (docs/dataset-format.md): an obj_id's model is the one of the first item that has it, and
// an item whose model of that obj_id differs (beyond 10⁻⁴ of its size) is refused.
#pragma once

#include <atomic>
#include <cstddef>
#include <functional>
#include <optional>

#include "integrator/dataset/manifest.h"

namespace camsim {

struct DatasetCheckOptions {
  std::function<void(std::size_t, std::size_t)> onChecked;  // (items checked, items)
  // Each item's estimated memory is held to it (none: the default limit; resource_guard.h).
  std::optional<double> maxMemoryGb;
  int threads = 0;                            // 0: all cores
  const std::atomic<bool>* cancel = nullptr;  // looked at before each item
};

// The first error in item order is thrown (InputError), named by the manifest's line where
// the manifest set the key. False when cancelled before every item was checked (a 100,000-
// item manifest takes minutes: found by probing, SIGTERM waited for all of them).
bool checkDataset(const Manifest& manifest, const DatasetCheckOptions& options = {});

}  // namespace camsim
