// `camsim merge PART... [-o DIR] [--scene FILE] [--ocio-config FILE] [--display D]
// [--view V] [--look L] [--aov-previews]`: the tile parts of one frame (camsim render
// --tiles k/M, integrator/capture/tile_parts.h) put back together. It checks that the
// parts are all of one render and that every share 0..M-1 is there once, assembles the
// films tile by tile, loads the scene the parts name again (camsim:scene as the render was
// given it, relative to the current directory, or --scene FILE; the same FNV-1a as the
// parts' or an error) with the render's overrides (camsim:overrides), runs the rest of the
// capture (finishCapture: metering, brackets, noise, ISP, picture) and writes what
// `camsim render --reproducible` writes, byte for byte, through one OutputSet. Any error
// (InputError naming the file: exit code 2) leaves nothing written.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace camsim {

struct MergeArgs {
  std::vector<std::string> parts;
  std::string outputDir = "out";
  std::optional<std::string> scene;  // none: the parts' camsim:scene
  // Output transform (OpenColorIO) and previews, as camsim render takes them.
  std::string ocioConfig, display, view, look;
  bool aovPreviews = false;
  bool help = false;
};

// args[0] == "merge". UsageError on bad usage.
MergeArgs parseMergeArgs(const std::vector<std::string>& args);
std::string mergeUsageText();

// Merges and writes; `log` gets what was done. Throws InputError (nothing written then).
// Returns the files written.
std::vector<std::filesystem::path> runMerge(const MergeArgs& args, std::ostream& log);

// Entry point from main(): parses `args` (args[0] == "merge"), runs, returns the exit code.
int runMergeCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& log);

}  // namespace camsim
