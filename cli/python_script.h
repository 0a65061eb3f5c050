// Running the plot scripts that `camsim ptc` and `camsim bench` embed: Debian's
// /usr/bin/python3 (which has python3-matplotlib), or $CAMSIM_PYTHON.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace camsim {

// The interpreter if it can import matplotlib, else nothing (plots are then skipped).
std::optional<std::string> pythonWithMatplotlib();

// Runs `python -c script args…` (no shell) and waits; throws std::runtime_error if it
// fails. Its output goes to camsim's stdout/stderr.
void runPythonScript(const std::string& python, std::string_view script,
                     const std::vector<std::string>& args);

}  // namespace camsim
