// camsim: command-line entry point. The only place that turns errors into exit codes:
// 0 success, 1 internal error, 2 bad input, 128 + signal when interrupted (130 SIGINT,
// 143 SIGTERM).
#include <csignal>
#include <cstdio>
#include <exception>
#include <iostream>

#include "cli/args.h"
#include "cli/bench_command.h"
#include "cli/dataset_command.h"
#include "cli/expose_command.h"
#include "cli/merge_command.h"
#include "cli/mtf_command.h"
#include "cli/psf_command.h"
#include "cli/ptc_command.h"
#include "cli/render_command.h"
#include "sensor/base/input_error.h"

namespace {

std::atomic<bool> gCancel{false};
std::atomic<int> gSignal{0};  // the signal that set gCancel

// The first SIGINT/SIGTERM asks the render to stop (it checks every 64 samples of a pixel,
// then writes NAME.partial.exr of the finished tiles and exits with 128 + the signal: 130,
// 143), `camsim dataset` to stop after its item, `camsim expose` to start no frame and
// remove its temporaries (nothing written); a second one, e.g. a second Ctrl-C, kills at once
// (temporaries left behind are removed by the next run into the same directory).
extern "C" void onSignal(int sig) {
  gSignal.store(sig);
  gCancel.store(true);
  std::signal(sig, SIG_DFL);  // async-signal-safe
}

void catchSignals() {
  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);
  static_assert(std::atomic<bool>::is_always_lock_free && std::atomic<int>::is_always_lock_free,
                "set from a signal handler");
}

int interruptedExitCode() {
  return 128 + (gSignal.load() ? gSignal.load() : SIGINT);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  try {
    if (!args.empty() && args[0] == "ptc") return camsim::runPtcCommand(args, std::cout, std::cerr);
    if (!args.empty() && args[0] == "expose") {
      catchSignals();
      return camsim::runExposeCommand(args, std::cout, std::cerr, &gCancel, &gSignal);
    }
    if (!args.empty() && args[0] == "merge")
      return camsim::runMergeCommand(args, std::cout, std::cerr);
    if (!args.empty() && args[0] == "dataset") {
      catchSignals();
      return camsim::runDatasetCommand(args, std::cout, std::cerr, &gCancel, &gSignal);
    }
    if (!args.empty() && args[0] == "mtf") return camsim::runMtfCommand(args, std::cout, std::cerr);
    if (!args.empty() && args[0] == "psf") return camsim::runPsfCommand(args, std::cout, std::cerr);
    if (!args.empty() && args[0] == "bench")
      return camsim::runBenchCommand(args, std::cout, std::cerr);
    const camsim::Command cmd = camsim::parseArgs(args);
    switch (cmd.kind) {
      case camsim::Command::Kind::kHelp:
        std::cout << (cmd.help.empty() ? camsim::usageText() : cmd.help);
        return 0;
      case camsim::Command::Kind::kVersion:
        std::cout << "camsim " << CAMSIM_VERSION << "\n";
        return 0;
      case camsim::Command::Kind::kRender: {
        catchSignals();
        const auto result = camsim::runRender(cmd.render, std::cerr, &gCancel);
        return result.cancelled ? interruptedExitCode() : 0;
      }
    }
  } catch (const camsim::UsageError& e) {
    std::cerr << "camsim: " << e.what() << "\n";
    return 2;
  } catch (const camsim::InputError& e) {
    std::cerr << "camsim: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "camsim: internal error: " << e.what() << "\n";
    return 1;
  }
  return 1;
}
