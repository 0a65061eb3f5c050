// scene_error_cases: prints the scene loader's malformed-scene cases
// (scene_loader_error_cases.h) as JSON Lines — name, text, line, column, key, message — so
// that the Python module's tests (python/tests/test_errors.py) check the very same cases
// against the same expected locations as SceneLoaderErrorTest.
#include <iostream>

#include "sensor/io/json_writer.h"
#include "tests/integrator/scene/scene_loader_error_cases.h"

int main() {
  for (const camsim::test::ErrorCase& c : camsim::test::kErrorCases) {
    camsim::JsonObject o;
    o.set("name", c.name)
        .set("text", c.text)
        .setInteger("line", static_cast<std::uint64_t>(c.line))
        .setInteger("column", static_cast<std::uint64_t>(c.column))
        .set("key", c.key)
        .set("message", c.message);
    std::cout << o.line() << "\n";
  }
  return 0;
}
