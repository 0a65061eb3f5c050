// `camsim render`: parse the scene and overrides → capture() → writeCapture() → print
// (integrator/capture/): all outputs appear atomically. With --tiles k/M only that share
// of the tiles is rendered (renderCaptureFilms) and written as DIR/NAME.part-k-of-M.exr
// (integrator/capture/tile_parts.h), for camsim merge (merge_command.h).
#pragma once

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

#include "cli/args.h"

namespace camsim {

struct CaptureResult;
struct SceneDescription;

// args.scene (none: the default scene) loaded, with the command line's overrides applied.
// InputError for a bad scene or an override the scene cannot take (applyOverrides).
SceneDescription loadRenderScene(const RenderArgs& args);
// The notes a capture prints: auto-exposure's choice, frames with clipped photosites.
void printCaptureNotes(const CaptureResult& result, std::ostream& log);

struct RenderCommandResult {
  std::vector<std::filesystem::path> files;  // written, final names
  bool cancelled = false;
};

// Throws InputError on bad input (nothing is written then), including a render whose
// estimated memory exceeds the limit (resource_guard.h), before any work. `cancel` may stop
// the render; a cancelled render writes no file under a final name, only NAME.partial.exr
// with the tiles that had finished (if any). Temporaries of killed runs in the output
// directory are removed (OutputSet::cleanStaleTemporaries).
RenderCommandResult runRender(const RenderArgs& args, std::ostream& log,
                              const std::atomic<bool>* cancel = nullptr);

}  // namespace camsim
