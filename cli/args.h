// Command-line parsing for `camsim`. Bad usage throws UsageError (exit code 2).
#pragma once

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "integrator/scene/overrides.h"
#include "sensor/base/share.h"

namespace camsim {

class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct RenderArgs {
  std::optional<std::string> scene;  // none: the built-in default scene
  std::string outputDir = "out";
  int threads = 0;                    // 0: all cores
  std::optional<double> maxMemoryGb;  // none: 75 % of physical memory (resource_guard.h)
  // The scene overrides (--spp, --seed, --exposure-time-s, --f-number, --iso, --noise,
  // --noise-seed, --sensor, --pose): integrator/scene/overrides.h's table.
  Overrides overrides;
  // Output transform (OpenColorIO): empty = the config's defaults.
  std::string ocioConfig, display, view, look;
  bool aovPreviews = false;  // --aov-previews
  // --reproducible: no render time in NAME.exr and NAME.json (CaptureOutputOptions).
  bool reproducible = false;
  // --tiles k/M: render share k of M of the tiles into a part (tile_parts.h).
  std::optional<Share> tiles;
};

struct Command {
  enum class Kind { kHelp, kVersion, kRender } kind = Kind::kHelp;
  RenderArgs render;
  std::string help;  // kHelp of a command (render --help): its text; empty: usageText()
};

Command parseArgs(const std::vector<std::string>& args);  // args without argv[0]
// `camsim --help`: every command with its summary (cli/command_line.h).
std::string usageText();
// `camsim render --help`, from render's option table.
std::string renderUsageText();
// An integer flag value in [lo, hi]; UsageError naming the flag otherwise.
std::int64_t parseInteger(const std::string& flag, const std::string& text, std::int64_t lo,
                          std::int64_t hi);

// "k/M" of a share flag (--tiles, --shard): sensor/base/share.h's parseShare, its
// InputError as UsageError "--tiles: expects k/M (share k of M, 0 <= k < M, …), got '3/2'".
Share parseShareOption(const std::string& flag, const std::string& text);

// The override whose flag is `flag` ("--f-number"; "--exposure-time" is --exposure-time-s's
// old name), or nullptr.
const OverrideSetting* overrideOfFlag(const std::string& flag);
// The flag's value into o: UsageError "--f-number: value 0.3 is out of range [0.5, 10000]".
void parseOverride(Overrides& o, const OverrideSetting& setting, const std::string& flag,
                   const std::string& text);

}  // namespace camsim
