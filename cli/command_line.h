// Every command's option table (issue 35, "one option table per command"): each command
// declares its options once on a CLI11 app (Debian's libcli11-dev); the same table parses
// the arguments and prints the command's --help. The override flags come from the library's
// overrides table (integrator/scene/overrides.h), so their names, value names and ranges are
// defined there once.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "integrator/scene/overrides.h"

namespace camsim {

// An app for `camsim NAME`: its description first in --help, -h/--help, no config files.
std::unique_ptr<CLI::App> newCommandApp(const std::string& name, const std::string& description);

// Parses args (args[0] is the command's name and is skipped) with app's table. Returns false
// when --help was given (print commandHelp then); UsageError (exit 2) naming the problem and
// "try 'camsim NAME --help'" on bad usage; a value's own check may throw UsageError too.
bool parseCommand(CLI::App& app, const std::vector<std::string>& args);
// The command's --help text, generated from its table.
std::string commandHelp(const CLI::App& app);

// The override flags of overrides.h's table (--spp, --seed, --exposure-time-s, …), parsed and
// range-checked by the library into `o` (UsageError "--f-number: value 0.3 is out of range
// [0.5, 10000]"). Grouped under "Scene overrides" in --help, each with its range.
void addOverrideOptions(CLI::App& app, Overrides& o);

// The output-transform options of render, merge and dataset (--ocio-config, --display,
// --view, --look; empty: the config's defaults).
void addPictureOptions(CLI::App& app, std::string& ocioConfig, std::string& display,
                       std::string& view, std::string& look);

// -o/--output DIR (non-empty).
void addOutputOption(CLI::App& app, std::string& dir, const std::string& help);

// --threads N: worker threads in [1, kMaxThreads] (sensor/base/threads.h; UsageError otherwise); left as it is (0: all
// hardware threads) unless given. What the threads do goes in `help`'s tail.
void addThreadsOption(CLI::App& app, int& threads, const std::string& what);

// --max-memory-gb X (resource_guard.h): refuse `what` ("a render", "an item") whose
// estimated memory exceeds X GB.
void addMemoryLimitOption(CLI::App& app, std::optional<double>& gb, const std::string& what);

}  // namespace camsim
