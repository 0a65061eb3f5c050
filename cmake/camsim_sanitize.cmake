# Instrumented builds, applied directory-wide (add_compile_options / add_link_options) so
# every target added afterwards — sensor/, integrator/, cli/, bench/, tests/, fuzz/ — is
# built the same way. Third-party libraries (Embree, TBB, yaml-cpp, OpenEXR, GoogleTest)
# are the system's, not instrumented.
#
#   CAMSIM_SANITIZE=ON  AddressSanitizer + UndefinedBehaviorSanitizer, any error aborts
#                       (scripts/test.sh builds build-asan/ this way with Clang,
#                       RelWithDebInfo, and CAMSIM_FUZZ=ON: one build for both).
#   CAMSIM_FUZZ=ON      Clang only: the same sanitizers plus libFuzzer coverage
#                       instrumentation (-fsanitize=fuzzer-no-link) for the libraries;
#                       fuzz/ links the harnesses with -fsanitize=fuzzer.
set(CAMSIM_SANITIZER_FLAGS
    -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)

if(CAMSIM_FUZZ AND NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
  message(FATAL_ERROR "CAMSIM_FUZZ=ON needs Clang (libFuzzer); configure with "
                      "CC=clang CXX=clang++ in a fresh build directory")
endif()

if(CAMSIM_SANITIZE OR CAMSIM_FUZZ)
  if(CMAKE_BUILD_TYPE STREQUAL "Release")
    message(STATUS "camsim: sanitizers on a Release build; RelWithDebInfo gives line numbers")
  endif()
  add_compile_options(${CAMSIM_SANITIZER_FLAGS})
  add_link_options(${CAMSIM_SANITIZER_FLAGS})
endif()
if(CAMSIM_FUZZ)
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()
