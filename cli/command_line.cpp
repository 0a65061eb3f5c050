#include "cli/command_line.h"

#include "cli/args.h"
#include "integrator/capture/resource_guard.h"
#include "sensor/base/threads.h"

#include <algorithm>
#include <charconv>

namespace camsim {
namespace {

std::string commandName(const CLI::App& app) {
  return app.get_name();
}

}  // namespace

std::unique_ptr<CLI::App> newCommandApp(const std::string& name, const std::string& description) {
  auto app = std::make_unique<CLI::App>(description, "camsim " + name);
  app->set_help_flag("-h,--help", "print this help and exit");
  app->get_formatter()->column_width(24);
  return app;
}

bool parseCommand(CLI::App& app, const std::vector<std::string>& args) {
  // CLI11 takes the arguments in reverse order.
  std::vector<std::string> reversed(args.rbegin(), args.rend());
  if (!reversed.empty()) reversed.pop_back();  // the command's name
  // Extras are collected rather than thrown: CLI11's ExtrasError lists them all, in its
  // reversed order ("x.exr --out" for `--out x.exr`); the user is told the first one they
  // typed, an unknown option before a stray argument (the value after it is the option's).
  app.allow_extras(true);
  try {
    app.parse(reversed);
  } catch (const CLI::CallForHelp&) {
    return false;
  } catch (const CLI::ParseError& e) {
    throw UsageError(std::string(e.what()) + " (try '" + commandName(app) + " --help')");
  }
  const std::vector<std::string> extras = app.remaining();
  if (!extras.empty()) {
    const auto option = std::find_if(extras.begin(), extras.end(), [](const std::string& x) {
      return x.size() > 1 && x[0] == '-';
    });
    const std::string help = "' (try '" + commandName(app) + " --help')";
    if (option != extras.end())
      throw UsageError("unknown option '" + option->substr(0, option->find('=')) + help);
    throw UsageError("unexpected argument '" + extras.front() + help);
  }
  return true;
}

std::string commandHelp(const CLI::App& app) {
  return app.help();
}

void addOverrideOptions(CLI::App& app, Overrides& o) {
  for (const OverrideSetting& s : overrideSettings()) {
    const std::string flag = overrideFlag(s);
    // --exposure-time: --exposure-time-s's name before the table named it after its key.
    const std::string names = flag + (s.key == "exposure_time_s" ? ",--exposure-time" : "");
    std::string help = std::string(s.help);
    if (s.type == OverrideType::kInteger || s.type == OverrideType::kNumber)
      help += " " + overrideRangeText(s);
    else if (s.type == OverrideType::kNoise)
      help += ": " + overrideRangeText(s);
    app.add_option_function<std::string>(
           names, [&o, &s, flag](const std::string& text) { parseOverride(o, s, flag, text); },
           help)
        ->type_name(std::string(s.valueName))
        ->group("Scene overrides");
  }
}

void addPictureOptions(CLI::App& app, std::string& ocioConfig, std::string& display,
                       std::string& view, std::string& look) {
  const std::string group = "Output transform (OpenColorIO; docs/color-management.md)";
  app.add_option("--ocio-config", ocioConfig,
                 "OpenColorIO config for the picture (default: $OCIO, else luts/config.ocio)")
      ->type_name("FILE")
      ->group(group);
  app.add_option("--display", display, "display (default: the config's sRGB)")
      ->type_name("D")
      ->group(group);
  app.add_option("--view", view, "view (default: 'ACES 1.0 - SDR Video')")
      ->type_name("V")
      ->group(group);
  app.add_option("--look", look, "look (default: none)")->type_name("L")->group(group);
}

void addThreadsOption(CLI::App& app, int& threads, const std::string& what) {
  app.add_option_function<std::string>(
         "--threads",
         [&threads](const std::string& t) {
           threads = static_cast<int>(parseInteger("--threads", t, 1, kMaxThreads));
         },
         "worker threads [1, " + std::to_string(kMaxThreads) + "] (default: all cores); " + what)
      ->type_name("N");
}

void addMemoryLimitOption(CLI::App& app, std::optional<double>& gb, const std::string& what) {
  app.add_option_function<std::string>(
         "--max-memory-gb",
         [&gb](const std::string& t) {
           double v = -1.0;  // not a number: refused by the range
           const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
           if (ec != std::errc() || ptr != t.data() + t.size()) v = -1.0;
           try {
             gb = checkMaxMemoryGb(v, {}, "--max-memory-gb");
           } catch (const InputError& e) {
             throw UsageError("--max-memory-gb " + e.message() + ", got '" + t + "'");
           }
         },
         "refuse to start " + what +
             " whose estimated memory exceeds X GB (default: 75 % of physical memory)")
      ->type_name("X");
}

void addOutputOption(CLI::App& app, std::string& dir, const std::string& help) {
  app.add_option_function<std::string>(
         "-o,--output",
         [&dir](const std::string& text) {
           if (text.empty()) throw UsageError("-o/--output needs a non-empty directory");
           dir = text;
         },
         help)
      ->type_name("DIR");
}

}  // namespace camsim
