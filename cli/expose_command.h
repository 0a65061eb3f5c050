// `camsim expose ELECTRONS.exr [--sensor S] [--iso N] [--exposure-scale X] [--frames N]
// [--seed N] [--noise none|photon|full] [-o DIR]`: re-exposure without re-rendering
// (issue 37). The noise-free expected electrons a render wrote (NAME_raw.exr's
// electrons.<channel> layers) become N raw frames, each a DNG and a raw EXR as `camsim
// render` writes them, frame f with the noise of (seed, f). Reading, checking and writing
// are the library's (sensor/io/expose_file.h); this file parses the options, runs the frames
// in parallel and writes them all at once (OutputSet): an error leaves nothing written.
#pragma once

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "sensor/io/expose_file.h"

namespace camsim {

struct ExposeArgs {
  std::string input;  // the electrons EXR
  ExposeFileSettings settings;
  std::string outputDir = "out";
  int threads = 0;  // 0: all cores; the bytes do not depend on it
  bool help = false;
};

// args[0] == "expose". UsageError on bad usage (values are range-checked by the library).
ExposeArgs parseExposeArgs(const std::vector<std::string>& args);
std::string exposeUsageText();

// Exposes and writes; `log` gets progress and the files. Throws InputError (nothing written
// then). Returns the files written; nullopt when `cancel` was set (frames in flight finish,
// no other starts, and every temporary is removed: nothing written).
std::optional<std::vector<std::filesystem::path>> runExpose(
    const ExposeArgs& args, std::ostream& log, const std::atomic<bool>* cancel = nullptr);

// Entry point from main(): parses `args` (args[0] == "expose"), runs, returns the exit code
// (128 + *signal when cancelled).
int runExposeCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& log,
                     const std::atomic<bool>* cancel = nullptr,
                     const std::atomic<int>* signal = nullptr);

}  // namespace camsim
