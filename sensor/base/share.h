// Share: share k of M of a run of work items numbered 0, 1, 2, … — item i belongs to share
// i mod M — so that M processes, each given its own k, do every item exactly once between
// them. The one "k of M" type of every front end:
//   camsim render --tiles k/M   the image's 16 × 16 tiles (integrator/render/render.h)
//   camsim dataset --shard k/M  a manifest's items (integrator/dataset/dataset_run.h; also
//                               from Slurm's or Kubernetes' environment, cli/dataset_command.h)
//
// | field | range                      | default | meaning                          |
// |-------|----------------------------|---------|----------------------------------|
// | index | 0 ≤ index < count          | 0       | k: this share                    |
// | count | 1 ≤ count ≤ kMaxShareCount | 1       | M: how many shares; 1 = all work |
//
// Share k of M holds items k, k + M, k + 2M, …; of n items that is ⌈(n − k) / M⌉ (0 if
// k ≥ n).
#pragma once

#include <cstdint>
#include <string>

namespace camsim {

constexpr int kMaxShareCount = 1 << 20;

struct Share {
  int index = 0, count = 1;

  bool owns(std::int64_t item) const { return item % count == index; }
  // How many of n items (0 … n − 1) the share holds, and its i-th one (0 ≤ i < that).
  int itemsOf(int n) const { return index < n ? (n - index + count - 1) / count : 0; }
  int item(int i) const { return index + i * count; }
};

// "k/M": two decimal integers, 0 ≤ k < M ≤ kMaxShareCount, nothing else (no sign, no
// blank). InputError naming `key` (the flag or setting that gave the text) and the range
// otherwise: "expects k/M (share k of M, 0 <= k < M, 1 <= M <= 1048576), got '3/2'".
Share parseShare(const std::string& text, const std::string& key);

}  // namespace camsim
