# Whether the `freeplay` Python module (python/, docs/python.md) is built: FREEPLAY_PYTHON_MODULE. A Python extension
# is a shared object; the libraries it links are position-independent like the whole build (root CMakeLists.txt).
# Built when Debian's pybind11-dev and python3-dev are present (scripts/setup.sh), against /usr/bin/python3.
option(FREEPLAY_PYTHON "Build the freeplay Python module when pybind11 and Python's headers are installed" ON)
set(FREEPLAY_PYTHON_MODULE OFF)
if(NOT FREEPLAY_PYTHON OR FREEPLAY_SANITIZE OR FREEPLAY_FUZZ)
  return()  # sanitized and fuzzing builds leave it out (an instrumented extension needs a preloaded runtime)
endif()
if(NOT DEFINED Python_EXECUTABLE AND EXISTS /usr/bin/python3)
  set(Python_EXECUTABLE /usr/bin/python3)  # Debian's interpreter: the one with python3-numpy, -pandas, -pytest
endif()
find_package(Python COMPONENTS Interpreter Development.Module QUIET)
if(NOT Python_Development.Module_FOUND)
  message(STATUS "freeplay Python module: skipped (no python3-dev; scripts/setup.sh installs it)")
  return()
endif()
set(PYBIND11_FINDPYTHON ON)
find_package(pybind11 2.10 CONFIG QUIET)
if(NOT pybind11_FOUND)
  message(STATUS "freeplay Python module: skipped (no pybind11-dev; scripts/setup.sh installs it)")
  return()
endif()
set(FREEPLAY_PYTHON_MODULE ON)
