// Fixture of Architecture.FrontEndIncludingAnotherIsRejected: python/ including cli/.
#include "cli/render_command.h"
#include "integrator/capture/capture.h"
#include "python/bindings.h"
