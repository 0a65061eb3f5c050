// Checking a dataset's items before anything is written or rendered (runDataset, `camsim
// dataset --check`): the base scene, then every item resolved and loaded (on all cores) with
// its pose exports' models made, and with `exports: [bop]` one model per obj_id across the
// items — their train_pbr/ scenes gather into one BOP dataset under one models/
// (docs/dataset-format.md): an obj_id's model is the one of the first item that has it, and
// an item whose model of that obj_id differs (beyond 10⁻⁴ of its size) is refused.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>

#include "integrator/dataset/manifest.h"

namespace camsim {

// The first error in item order is thrown (InputError), named by the manifest's line where
// the manifest set the key. onChecked(items checked, items). Each item's estimated memory is
// held to maxMemoryGb (none: the default limit; resource_guard.h).
void checkDataset(const Manifest& manifest,
                  const std::function<void(std::size_t, std::size_t)>& onChecked = {},
                  std::optional<double> maxMemoryGb = std::nullopt);

}  // namespace camsim
