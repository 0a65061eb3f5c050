// Fixture of Architecture.FrontEndIncludingAnotherIsRejected: bench/ including python/.
#include "bench/other.h"
#include "python/bindings.h"
