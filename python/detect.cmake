# Included by the top-level CMakeLists.txt before the layers: finds Python,
# pybind11 and NumPy and sets RTCSIM_BUILD_PYTHON from the RTCSIM_PYTHON
# option (on when they are found, unless RTCSIM_PYTHON=OFF). The module links
# the static layer libraries into a shared object, so they are built
# position-independent when it is on.

# Prefer an interpreter with NumPy: a python3 without it (pyenv, a venv) may
# come first on PATH while Debian's /usr/bin/python3 has python3-numpy.
if(NOT Python_EXECUTABLE)
  find_program(RTCSIM_PATH_PYTHON3 NAMES python3 NO_CACHE)
  foreach(candidate IN ITEMS ${RTCSIM_PATH_PYTHON3} /usr/bin/python3)
    if(EXISTS "${candidate}")
      execute_process(COMMAND "${candidate}" -c "import numpy"
                      RESULT_VARIABLE rtcsim_numpy_rc OUTPUT_QUIET ERROR_QUIET)
      if(rtcsim_numpy_rc EQUAL 0)
        set(Python_EXECUTABLE "${candidate}" CACHE FILEPATH "Python interpreter of the rtcsim module")
        break()
      endif()
    endif()
  endforeach()
endif()

find_package(Python 3.8 COMPONENTS Interpreter Development.Module QUIET)
if(Python_FOUND)
  find_package(pybind11 2.6 CONFIG QUIET)  # Debian: pybind11-dev (uses the Python found above)
  execute_process(COMMAND "${Python_EXECUTABLE}" -c "import numpy"
                  RESULT_VARIABLE rtcsim_numpy_rc OUTPUT_QUIET ERROR_QUIET)
endif()
set(rtcsim_python_found OFF)
if(Python_FOUND AND pybind11_FOUND AND rtcsim_numpy_rc EQUAL 0)
  set(rtcsim_python_found ON)
endif()

# AUTO (the default) re-detects at every configure, so a build directory made
# before scripts/setup installed the packages picks the module up later.
set(RTCSIM_PYTHON AUTO CACHE STRING
    "Build the Python module rtcsim: AUTO (when python3-dev, pybind11-dev and python3-numpy are found), ON or OFF")
set_property(CACHE RTCSIM_PYTHON PROPERTY STRINGS AUTO ON OFF)
if(RTCSIM_PYTHON STREQUAL "AUTO")
  set(RTCSIM_BUILD_PYTHON ${rtcsim_python_found})
  if(RTCSIM_SANITIZE OR RTCSIM_FUZZ)
    # An ASan-instrumented extension needs the runtime preloaded into python:
    # sanitizer and fuzz builds leave the module to the Release build.
    set(RTCSIM_BUILD_PYTHON OFF)
  endif()
elseif(RTCSIM_PYTHON)
  if(NOT rtcsim_python_found)
    message(FATAL_ERROR "RTCSIM_PYTHON=ON needs python3-dev, pybind11-dev and python3-numpy "
                        "(scripts/setup installs them)")
  endif()
  set(RTCSIM_BUILD_PYTHON ON)
else()
  set(RTCSIM_BUILD_PYTHON OFF)
endif()
if(RTCSIM_BUILD_PYTHON)
  set(CMAKE_POSITION_INDEPENDENT_CODE ON)
endif()
