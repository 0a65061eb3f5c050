# The Python module's switch (python/CMakeLists.txt builds it): CAMSIM_PYTHON defaults to ON
# when pybind11 (CONFIG), Python 3's interpreter and module development files and NumPy are
# all found, Debian's /usr/bin/python3 preferred. It is OFF by default in the sanitizer and
# fuzz builds: an ASan-built extension cannot be imported into an unsanitised interpreter.
# With it on, every library is position-independent (a shared module links them); see the
# note on -fno-semantic-interposition below.
set(camsim_python_default OFF)
set(camsim_python_why "")
if(CAMSIM_SANITIZE OR CAMSIM_FUZZ)
  set(camsim_python_why "not in sanitizer or fuzz builds")
else()
  if(NOT DEFINED Python3_EXECUTABLE AND EXISTS /usr/bin/python3)
    set(Python3_EXECUTABLE /usr/bin/python3)
  endif()
  find_package(Python3 COMPONENTS Interpreter Development.Module NumPy QUIET)
  find_package(pybind11 CONFIG QUIET)
  if(Python3_FOUND AND Python3_NumPy_FOUND AND pybind11_FOUND)
    set(camsim_python_default ON)
  else()
    set(camsim_python_why "needs pybind11-dev, python3-dev and python3-numpy (apt-get install "
                          "pybind11-dev python3-dev python3-numpy)")
  endif()
endif()
option(CAMSIM_PYTHON "Build the Python module camsim (python/, docs/python.md)"
       ${camsim_python_default})
if(CAMSIM_PYTHON)
  if(NOT (Python3_FOUND AND Python3_NumPy_FOUND AND pybind11_FOUND))
    message(FATAL_ERROR "CAMSIM_PYTHON=ON but ${camsim_python_why}; or configure with "
                        "-DCAMSIM_PYTHON=OFF")
  endif()
  message(STATUS "camsim Python module: on (${Python3_EXECUTABLE}, NumPy ${Python3_NumPy_VERSION}, "
                 "pybind11 ${pybind11_VERSION})")
  set(CMAKE_POSITION_INDEPENDENT_CODE ON)
  # -fPIC lets GCC assume any exported function may be interposed at load time, which stops
  # it inlining them; nothing interposes camsim's functions, so keep the -fPIE code generation.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    add_compile_options(-fno-semantic-interposition)
  endif()
else()
  message(STATUS "camsim Python module: off (${camsim_python_why})")
endif()
