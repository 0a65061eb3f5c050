#include "cli/args.h"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "sensor/base/input_error.h"

namespace camsim {
namespace {

double parsePositive(const std::string& flag, const std::string& text, double hi) {
  double v = 0.0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || ptr != text.data() + text.size() || !std::isfinite(v) || v <= 0.0 ||
      v > hi)
    throw UsageError(flag + " expects a positive number (at most " + std::to_string(hi) +
                     "), got '" + text + "'");
  return v;
}

// The override flags' lines of the usage text, from overrides.h's table.
std::string overrideUsageLines() {
  std::string out;
  for (const OverrideSetting& s : overrideSettings()) {
    std::string left = "  " + overrideFlag(s) + " " + std::string(s.valueName);
    left.resize(std::max<std::size_t>(left.size() + 1, 21), ' ');
    std::string range = overrideRangeText(s);
    out += left + std::string(s.help) + "\n" + std::string(21, ' ') +
           (s.type == OverrideType::kInteger || s.type == OverrideType::kNumber ? "range " : "") +
           range + "\n";
  }
  return out;
}

// "k/M" with 0 ≤ k < M.
std::pair<int, int> parseTiles(const std::string& flag, const std::string& text) {
  const std::size_t slash = text.find('/');
  if (slash == std::string::npos)
    throw UsageError(flag + " expects k/M (share k of M, 0 <= k < M), got '" + text + "'");
  const int m = static_cast<int>(parseInteger(flag + " M", text.substr(slash + 1), 1, 1 << 20));
  const int k = static_cast<int>(parseInteger(flag + " k", text.substr(0, slash), 0, m - 1));
  return {k, m};
}

}  // namespace

const OverrideSetting* overrideOfFlag(const std::string& flag) {
  if (flag == "--exposure-time") return findOverrideSetting("exposure_time_s");  // its old name
  for (const OverrideSetting& s : overrideSettings())
    if (overrideFlag(s) == flag) return &s;
  return nullptr;
}

void parseOverride(Overrides& o, const OverrideSetting& setting, const std::string& flag,
                   const std::string& text) {
  try {
    const OverrideSource source{SourceLocation{"", 0, 0}, flag};
    setOverrideText(o, setting, text, source);
  } catch (const InputError& e) {
    throw UsageError(flag + ": " + e.message());
  }
}

std::int64_t parseInteger(const std::string& flag, const std::string& text, std::int64_t lo,
                          std::int64_t hi) {
  std::int64_t value = 0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || ptr != text.data() + text.size())
    throw UsageError(flag + " expects an integer, got '" + text + "'");
  if (value < lo || value > hi)
    throw UsageError(flag + " must be in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                     "], got " + text);
  return value;
}

std::string usageText() {
  return "camsim — camera-sensor physically based image simulator\n"
         "\n"
         "usage:\n"
         "  camsim render [SCENE] [-o DIR] [--threads N] [--max-memory-gb X]\n"
         "                [--spp N] [--seed N] [--exposure-time-s S] [--f-number N] [--iso N]\n"
         "                [--noise none|photon|full] [--noise-seed N] [--sensor MODEL]\n"
         "                [--pose POSE]\n"
         "                [--ocio-config FILE] [--display D] [--view V] [--look L]\n"
         "                [--aov-previews] [--reproducible] [--tiles k/M]\n"
         "  camsim merge PART... [-o DIR] [--scene FILE] [--ocio-config FILE] [--display D]\n"
         "               [--view V] [--look L] [--aov-previews]\n"
         "                                          (render --tiles parts: camsim merge --help)\n"
         "  camsim ptc SENSOR [-o DIR] [--seed N]   (photon transfer: camsim ptc --help)\n"
         "  camsim bench [--quick] [--out DIR] [--scenes a,b] [--max-spp N] ...\n"
         "                                          (speed against error: camsim bench --help)\n"
         "  camsim --help | --version\n"
         "\n"
         "render  renders SCENE (YAML or JSON, see docs/scene-format.md), or the built-in\n"
         "        Cornell box when no SCENE is given, and writes into DIR (default: out/):\n"
         "          NAME.exr  scene-linear OpenEXR: R,G,B linear Rec.709 and XYZ.X/Y/Z, absolute\n"
         "                    units (energy per photosite, Y in lm·s), with metadata\n"
         "          NAME.png  the picture through OpenColorIO (display/view/look below)\n"
         "          NAME.json every camera, sensor, ISP and colour setting used, and the\n"
         "                    files the scene loader read (input_files)\n"
         "        and with a sensor in the scene also NAME.dng, NAME_raw.exr (raw DN + electrons)\n"
         "        and NAME_acescg.exr (the developed scene-linear ACEScg image)\n"
         "  -o, --output DIR   output directory (created if missing)\n" +
         overrideUsageLines() +
         "  --threads N        worker threads (default: all cores); the image does not depend on "
         "it\n"
         "  --ocio-config FILE OpenColorIO config for the PNG (default: $OCIO, else "
         "luts/config.ocio)\n"
         "  --display D, --view V, --look L   output transform (default: the config's sRGB,\n"
         "                     'ACES 1.0 - SDR Video', no look; see docs/color-management.md)\n"
         "  --aov-previews     also write NAME_<layer>.png false-colour quick looks of the\n"
         "                     scene's ground-truth layers (depth, normal, ids, motion…)\n"
         "  --max-memory-gb X  refuse to start a render whose estimated memory exceeds X GB\n"
         "                     (default: 75 % of physical memory)\n"
         "  --reproducible     leave the render time out of NAME.exr and NAME.json, so that the\n"
         "                     same scene, seed and build give the same bytes in every file\n"
         "  --tiles k/M        render only share k of M of the image's 16x16 tiles (those t\n"
         "                     with t % M == k) and write just DIR/NAME.part-k-of-M.exr;\n"
         "                     camsim merge PART... assembles the M parts and writes exactly\n"
         "                     what render --reproducible writes (docs/output.md)\n"
         "\n"
         "exit codes: 0 success, 1 internal error, 2 bad input (scene, files or arguments),\n"
         "            130 interrupted\n";
}

Command parseArgs(const std::vector<std::string>& args) {
  Command cmd;
  if (args.empty()) throw UsageError("no command given (try 'camsim --help')");
  const std::string& first = args[0];
  if (first == "--help" || first == "-h" || first == "help") return cmd;
  if (first == "--version") {
    cmd.kind = Command::Kind::kVersion;
    return cmd;
  }
  if (first != "render") throw UsageError("unknown command '" + first + "' (try 'camsim --help')");
  cmd.kind = Command::Kind::kRender;
  RenderArgs& r = cmd.render;
  for (size_t i = 1; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> const std::string& {
      if (i + 1 >= args.size()) throw UsageError(a + " needs a value");
      return args[++i];
    };
    if (a == "--help" || a == "-h") {
      cmd.kind = Command::Kind::kHelp;
      return cmd;
    } else if (a == "-o" || a == "--output") {
      r.outputDir = value();
      if (r.outputDir.empty()) throw UsageError(a + " needs a non-empty directory");
    } else if (const OverrideSetting* o = overrideOfFlag(a)) {
      parseOverride(r.overrides, *o, a, value());
    } else if (a == "--threads") {
      r.threads = static_cast<int>(parseInteger(a, value(), 1, 1024));
    } else if (a == "--max-memory-gb") {
      r.maxMemoryGb = parsePositive(a, value(), 1e9);
    } else if (a == "--ocio-config") {
      r.ocioConfig = value();
    } else if (a == "--display") {
      r.display = value();
    } else if (a == "--view") {
      r.view = value();
    } else if (a == "--look") {
      r.look = value();
    } else if (a == "--aov-previews") {
      r.aovPreviews = true;
    } else if (a == "--reproducible") {
      r.reproducible = true;
    } else if (a == "--tiles") {
      r.tiles = parseTiles(a, value());
    } else if (!a.empty() && a[0] == '-') {
      throw UsageError("unknown option '" + a + "' (try 'camsim --help')");
    } else if (!r.scene) {
      r.scene = a;
    } else {
      throw UsageError("more than one scene given: '" + *r.scene + "' and '" + a + "'");
    }
  }
  if (r.tiles && (r.aovPreviews || !r.ocioConfig.empty() || !r.display.empty() || !r.view.empty() ||
                  !r.look.empty()))
    throw UsageError(
        "--aov-previews, --ocio-config, --display, --view and --look shape the files camsim "
        "merge writes: give them to camsim merge, not to render --tiles");
  return cmd;
}

}  // namespace camsim
