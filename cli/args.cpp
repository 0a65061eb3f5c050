#include "cli/args.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <memory>

#include "cli/command_line.h"
#include "sensor/base/input_error.h"

namespace camsim {

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
    // A value the scene loader read (--projection) names its own key: camera.projection.k1.
    const bool ownKey = !e.key().empty() && e.key() != flag;
    throw UsageError(flag + ": " + (ownKey ? "key '" + e.key() + "': " : "") + e.message());
  }
}

Share parseShareOption(const std::string& flag, const std::string& text) {
  try {
    return parseShare(text, flag);
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

namespace {

// Every command, in the order `camsim --help` lists them, with its one-line summary (each
// command's own --help starts with the same line).
struct CommandSummary {
  const char* name;
  const char* summary;
};
constexpr CommandSummary kCommands[] = {
    {"render",
     "renders a scene (or the built-in Cornell box) into EXR, PNG, JSON and, with a "
     "sensor, DNG and raw files"},
    {"merge",
     "assembles the tile parts of `camsim render --tiles k/M` into what one render "
     "writes"},
    {"dataset",
     "renders the items of a dataset manifest (grids, random draws), sharded and "
     "resumable"},
    {"expose",
     "re-exposes a render's noise-free electrons (NAME_raw.exr) into N raw frames without "
     "rendering again"},
    {"ptc", "EMVA 1288 photon-transfer measurement of a sensor"},
    {"mtf", "ISO 12233 slanted-edge MTF (e-SFR) of a region of an image"},
    {"psf", "PSF images of a scene's lens at chosen field points and wavelengths"},
    {"bench", "speed against error of the renderer on reference scenes"},
};

std::unique_ptr<CLI::App> renderApp(RenderArgs& r) {
  auto app = newCommandApp("render", std::string(kCommands[0].summary) + ".");
  app->add_option_function<std::string>(
         "scene", [&r](const std::string& s) { r.scene = s; },
         "scene file, YAML or JSON (docs/scene-format.md); none: the built-in Cornell box")
      ->type_name("SCENE");
  addOutputOption(*app, r.outputDir, "output directory (created if missing; default: out)");
  addThreadsOption(*app, r.threads, "the image does not depend on it");
  addMemoryLimitOption(*app, r.maxMemoryGb, "a render");
  addOverrideOptions(*app, r.overrides);
  addPictureOptions(*app, r.ocioConfig, r.display, r.view, r.look);
  app->add_flag("--aov-previews", r.aovPreviews,
                "also write NAME_<layer>.png false-colour quick looks of the scene's "
                "ground-truth layers (depth, normal, ids, motion…)");
  app->add_flag("--reproducible", r.reproducible,
                "leave the render time out of NAME.exr and NAME.json, so that the same scene, "
                "seed and build give the same bytes in every file");
  app->add_option_function<std::string>(
         "--tiles", [&r](const std::string& t) { r.tiles = parseShareOption("--tiles", t); },
         "render only share k of M of the image's 16x16 tiles (those t with t % M == k) and "
         "write just DIR/NAME.part-k-of-M.exr; camsim merge PART... assembles the M parts "
         "(docs/output.md)")
      ->type_name("k/M");
  app->footer(
      "Writes into DIR:\n"
      "  NAME.exr   scene-linear OpenEXR: R,G,B linear Rec.709 and XYZ.X/Y/Z, absolute units\n"
      "             (energy per photosite, Y in lm·s), with metadata\n"
      "  NAME.png   the picture through OpenColorIO (display/view/look)\n"
      "  NAME.json  every camera, sensor, ISP and colour setting used, and the files the\n"
      "             scene loader read (input_files)\n"
      "and with a sensor in the scene also NAME.dng, NAME_raw.exr (raw DN + electrons) and\n"
      "NAME_acescg.exr (the developed scene-linear ACEScg image).\n"
      "Exit codes: 0 success, 1 internal error, 2 bad input (scene, files or arguments),\n"
      "130 interrupted.");
  return app;
}

}  // namespace

std::string usageText() {
  CLI::App app("camsim — camera-sensor physically based image simulator", "camsim");
  app.set_help_flag("-h,--help", "print this help and exit");
  app.add_flag("--version")->description("print the version and exit");
  for (const CommandSummary& c : kCommands) app.add_subcommand(c.name, c.summary);
  app.footer(
      "camsim COMMAND --help prints the command's options (generated from its option table).\n"
      "Exit codes: 0 success, 1 internal error, 2 bad input (scene, files or arguments),\n"
      "128 + signal when interrupted (130 SIGINT, 143 SIGTERM).");
  return app.help();
}

std::string renderUsageText() {
  RenderArgs r;
  return commandHelp(*renderApp(r));
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
  const std::unique_ptr<CLI::App> app = renderApp(r);
  if (!parseCommand(*app, args)) {
    cmd.kind = Command::Kind::kHelp;
    cmd.help = commandHelp(*app);
    return cmd;
  }
  if (r.tiles && (r.aovPreviews || !r.ocioConfig.empty() || !r.display.empty() || !r.view.empty() ||
                  !r.look.empty()))
    throw UsageError(
        "--aov-previews, --ocio-config, --display, --view and --look shape the files camsim "
        "merge writes: give them to camsim merge, not to render --tiles");
  return cmd;
}

}  // namespace camsim
