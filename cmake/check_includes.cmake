# The include rules of docs/architecture.md, checked on every source file of integrator/
# and sensor/ (run as a test: cmake -DSOURCE_DIR=… -P cmake/check_includes.cmake).
#
# 1. Sub-areas include only the sub-areas below them (ALLOWED_<area>); sensor/ never
#    includes integrator/. A file's own sub-area is always allowed.
# 2. No header includes a heavy dependency (Embree, OpenEXR/Imath, OpenColorIO, libtiff,
#    libpng, TBB, yaml-cpp): each lives in the .cpp files of the module that owns it.
#    KNOWN_HEADER_LEAKS would list accepted exceptions: there are none.
# 3. x86-specific code (builtins, target attributes, intrinsics headers and names) appears
#    only in sensor/base/simd.h, which has a portable path for each (CAMSIM_SIMD=OFF):
#    checked on every .h/.cpp of integrator/, sensor/, cli/, bench/, fuzz/ and tests/
#    (not tests/data/, whose fixtures break the rules on purpose).
# 4. pybind11 (and Python.h) is included only in python/, the Python module: no library,
#    CLI, benchmark, fuzz or test file includes it (python/ files are checked by rule 3).
# 5. The front ends stand side by side: cli/, python/ and bench/ include the library
#    (integrator/, sensor/) and their own folder, never each other. What two front ends
#    share belongs in the library. KNOWN_FRONT_END_INCLUDES would list accepted exceptions
#    ("file|front end"): there are none.
# Prints what it checked; any violation is a SEND_ERROR (the test fails, naming file, line
# and include).
cmake_minimum_required(VERSION 3.22)
if(NOT SOURCE_DIR)
  message(FATAL_ERROR "usage: cmake -DSOURCE_DIR=<camsim source> -P check_includes.cmake")
endif()

set(SENSOR_ALL sensor/base sensor/spectra sensor/model sensor/isp sensor/io sensor/measure)
set(ALLOWED_sensor/base "")
set(ALLOWED_sensor/spectra sensor/base)
set(ALLOWED_sensor/model sensor/base sensor/spectra)
set(ALLOWED_sensor/isp sensor/base sensor/spectra sensor/model)
set(ALLOWED_sensor/io sensor/base sensor/spectra sensor/model sensor/isp)
set(ALLOWED_sensor/measure sensor/base sensor/spectra sensor/model sensor/isp sensor/io)
set(ALLOWED_integrator/sampling ${SENSOR_ALL})
set(ALLOWED_integrator/geometry integrator/sampling ${SENSOR_ALL})
set(ALLOWED_integrator/textures integrator/sampling integrator/geometry ${SENSOR_ALL})
set(ALLOWED_integrator/camera integrator/sampling integrator/geometry ${SENSOR_ALL})
set(ALLOWED_integrator/materials integrator/sampling integrator/geometry integrator/textures
    ${SENSOR_ALL})
set(ALLOWED_integrator/lights integrator/sampling integrator/geometry integrator/textures
    ${SENSOR_ALL})
set(ALLOWED_integrator/scene integrator/sampling integrator/geometry integrator/textures
    integrator/camera integrator/materials integrator/lights ${SENSOR_ALL})
set(ALLOWED_integrator/render integrator/sampling integrator/geometry integrator/textures
    integrator/camera integrator/materials integrator/lights integrator/scene ${SENSOR_ALL})
set(ALLOWED_integrator/capture integrator/sampling integrator/geometry integrator/textures
    integrator/camera integrator/materials integrator/lights integrator/scene integrator/render
    ${SENSOR_ALL})
set(ALLOWED_integrator/measure integrator/sampling integrator/geometry integrator/textures
    integrator/camera integrator/materials integrator/lights integrator/scene integrator/render
    ${SENSOR_ALL})
set(ALLOWED_integrator/dataset integrator/sampling integrator/geometry integrator/textures
    integrator/camera integrator/materials integrator/lights integrator/scene integrator/render
    integrator/capture ${SENSOR_ALL})

set(HEAVY "embree3/|OpenEXR/|Imath/|Imf|OpenColorIO|tiffio|tiff\\.h|png\\.h|tbb/|oneapi/|yaml-cpp/|tiny_gltf|nlohmann/")
set(KNOWN_HEADER_LEAKS "")

set(SIMD_HEADER sensor/base/simd.h)
set(X86_ONLY "__builtin_ia32_|__builtin_cpu_(supports|is|init)|target(_clones)?\\(\"")
string(APPEND X86_ONLY "|#include <[a-z0-9]*(intrin|cpuid)\\.h>|(^|[^A-Za-z0-9_])_mm(256|512)?_")
string(APPEND X86_ONLY "|__m(128|256|512)")

file(GLOB_RECURSE files RELATIVE "${SOURCE_DIR}" "${SOURCE_DIR}/integrator/*.h"
     "${SOURCE_DIR}/integrator/*.cpp" "${SOURCE_DIR}/sensor/*.h" "${SOURCE_DIR}/sensor/*.cpp")
set(violations 0)
set(checked 0)
foreach(f IN LISTS files)
  string(REGEX MATCH "^(integrator|sensor)/[a-z_]+" area "${f}")
  if(NOT DEFINED ALLOWED_${area})
    message(SEND_ERROR "${f}: not in a documented sub-area (docs/architecture.md)")
    math(EXPR violations "${violations} + 1")
    continue()
  endif()
  math(EXPR checked "${checked} + 1")
  file(STRINGS "${SOURCE_DIR}/${f}" lines REGEX "^#include ")
  foreach(line IN LISTS lines)
    if(line MATCHES "^#include \"((integrator|sensor)/[a-z_]+)/")
      set(target "${CMAKE_MATCH_1}")
      if(NOT target STREQUAL area)
        list(FIND ALLOWED_${area} "${target}" found)
        if(found EQUAL -1)
          message(SEND_ERROR "${f}: '${line}': ${area} may not include ${target}")
          math(EXPR violations "${violations} + 1")
        endif()
      endif()
    elseif(line MATCHES "^#include \"(integrator|sensor)/")
      message(SEND_ERROR "${f}: '${line}': include a file in its sub-area folder")
      math(EXPR violations "${violations} + 1")
    endif()
    # tinygltf and its JSON library belong to the glTF reader alone.
    if(line MATCHES "^#include <(tiny_gltf|nlohmann/)" AND NOT f MATCHES "^integrator/scene/gltf_[a-z_]+\\.cpp$")
      message(SEND_ERROR "${f}: '${line}': only integrator/scene/gltf_*.cpp include tinygltf")
      math(EXPR violations "${violations} + 1")
    endif()
    if(f MATCHES "\\.h$" AND line MATCHES "^#include <(${HEAVY})")
      list(FIND KNOWN_HEADER_LEAKS "${f}" known)
      if(known EQUAL -1)
        message(SEND_ERROR "${f}: '${line}': a header must not expose a heavy dependency")
        math(EXPR violations "${violations} + 1")
      endif()
    endif()
  endforeach()
endforeach()

file(GLOB_RECURSE all_sources RELATIVE "${SOURCE_DIR}" "${SOURCE_DIR}/integrator/*.h"
     "${SOURCE_DIR}/integrator/*.cpp" "${SOURCE_DIR}/sensor/*.h" "${SOURCE_DIR}/sensor/*.cpp"
     "${SOURCE_DIR}/cli/*.h" "${SOURCE_DIR}/cli/*.cpp" "${SOURCE_DIR}/bench/*.h"
     "${SOURCE_DIR}/bench/*.cpp" "${SOURCE_DIR}/fuzz/*.h" "${SOURCE_DIR}/fuzz/*.cpp"
     "${SOURCE_DIR}/tests/*.h" "${SOURCE_DIR}/tests/*.cpp" "${SOURCE_DIR}/python/*.h"
     "${SOURCE_DIR}/python/*.cpp")
set(x86_checked 0)
set(FRONT_ENDS cli python bench)
set(KNOWN_FRONT_END_INCLUDES "")
set(front_end_checked 0)
foreach(f IN LISTS all_sources)
  string(REGEX MATCH "^[a-z]+" top "${f}")
  list(FIND FRONT_ENDS "${top}" is_front_end)
  if(NOT is_front_end EQUAL -1)
    math(EXPR front_end_checked "${front_end_checked} + 1")
    file(STRINGS "${SOURCE_DIR}/${f}" lines REGEX "^#include \"[a-z]+/")
    foreach(line IN LISTS lines)
      string(REGEX MATCH "^#include \"([a-z]+)/" unused "${line}")
      set(other "${CMAKE_MATCH_1}")
      list(FIND FRONT_ENDS "${other}" other_is_front_end)
      list(FIND KNOWN_FRONT_END_INCLUDES "${f}|${other}" known)
      if(NOT other STREQUAL top AND NOT other_is_front_end EQUAL -1 AND known EQUAL -1)
        message(SEND_ERROR "${f}: '${line}': the front end ${top}/ may not include ${other}/ "
                           "(what two front ends share belongs in the library)")
        math(EXPR violations "${violations} + 1")
      endif()
    endforeach()
  endif()
endforeach()
foreach(f IN LISTS all_sources)
  if(f STREQUAL SIMD_HEADER OR f MATCHES "^tests/data/")
    continue()
  endif()
  math(EXPR x86_checked "${x86_checked} + 1")
  file(STRINGS "${SOURCE_DIR}/${f}" hits REGEX "${X86_ONLY}")
  foreach(line IN LISTS hits)
    string(STRIP "${line}" line)
    message(SEND_ERROR "${f}: '${line}': x86-specific code belongs in ${SIMD_HEADER}")
    math(EXPR violations "${violations} + 1")
  endforeach()
  if(NOT f MATCHES "^python/")
    file(STRINGS "${SOURCE_DIR}/${f}" py REGEX "^#include [<\"](pybind11/|Python\.h)")
    foreach(line IN LISTS py)
      message(SEND_ERROR "${f}: '${line}': only python/ includes pybind11")
      math(EXPR violations "${violations} + 1")
    endforeach()
  endif()
endforeach()
message(STATUS "include rules: ${checked} files checked, x86 rule: ${x86_checked} files, "
               "front-end rule: ${front_end_checked} files; ${violations} violations")
