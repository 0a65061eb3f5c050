// `camsim bench --peer cycles`: camsim and Cycles on the same scene, side by side in one run.
//
// Per scene, each renderer renders (1) a reference: two halves of refSpp/2 spp (seeds 1001
// and 1002), cached in CACHE_DIR as peer-NAME-RENDERER-KEY.exr with channels A.R, A.G, A.B,
// A.Y, B.R, B.G, B.B, B.Y; and (2) a ladder of minSpp, 2·minSpp, … its top spp (seed 1),
// each timed. camsim: Sobol', renderXyz on the bench's XYZ film; Cycles: the translated
// scene (peer_cycles.h) run by `blender -b --factory-startup --python SCRIPT` (stdout and
// stderr in a log in the scratch directory, quoted in the error if Blender fails), one
// Blender process for the reference and one per ladder (after a 1-spp warm-up render).
// Both references come first (rendered or read from the cache), then the ladders. Rounds
// (PeerPlan::rounds, `--peer-rounds`, ≥ 1): the two ladders K times, Cycles' then camsim's in
// each round; each rung keeps its fastest time (keepFastest, peer_compare.h).
// KEY (FNV-1a 64): camsim's reference key text (bench_reference.h: version, scene text,
// input files, resolution, spp) plus, for Cycles, the translated script without its render
// list and the blender executable's size and modification time.
// Errors and the equal-error time: peer_compare.h.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>

#include "integrator/measure/peer_compare.h"
#include "integrator/scene/scene_description.h"

namespace camsim {

struct PeerPlan {
  int refSpp = 4096;       // total over the two halves
  int minSpp = 16;         // the ladders' first rung
  int cyclesMaxSpp = 256;  // Cycles' top: the target error
  int camsimMaxSpp = 1024;
  int threads = 1;
  std::optional<int> maxDepth;  // overrides the scene's (Cycles: − 1)
  int rounds = 1;  // timed ladders per renderer, taking turns; each rung keeps its fastest
  std::filesystem::path cacheDir, scratchDir;
  std::string blender = "blender";  // the executable (a path from findBlender)
};

struct PeerInput {
  std::string name, sceneText;
  SceneDescription description;  // at the bench resolution
};

// The first executable `blender` on $PATH, or nothing.
std::optional<std::string> findBlender();

// Translates (InputError if the scene cannot be), renders and compares one scene.
// std::runtime_error if Blender fails (its log's tail in the message).
PeerSceneResult runPeerScene(const PeerInput& input, const PeerPlan& plan, std::ostream& log);

}  // namespace camsim
