// Fixture of Architecture.FrontEndIncludingAnotherIsRejected: cli/ including bench/.
#include "bench/bench_command.h"
#include "cli/args.h"
#include "sensor/base/format.h"
