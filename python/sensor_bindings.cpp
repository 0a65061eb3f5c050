// The sensor on its own — expose/develop/display: issue 23 item 4 (written there; this is
// the hook module.cpp calls).
#include "python/bindings.h"

// expose/develop/display: issue 23 item 4
void camsim::python::bindSensorFunctions([[maybe_unused]] pybind11::module_& m) {}
