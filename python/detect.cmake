# Included by the top-level CMakeLists.txt before the layers: finds Python and
# pybind11 and sets RTCSIM_PYTHON (on by default when both are found). The
# module links the static layer libraries into a shared object, so they are
# built position-independent when it is on.

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
endif()
set(rtcsim_python_default OFF)
if(Python_FOUND AND pybind11_FOUND)
  set(rtcsim_python_default ON)
endif()
option(RTCSIM_PYTHON "Build the Python module rtcsim (pybind11, NumPy)" ${rtcsim_python_default})
if(RTCSIM_PYTHON)
  if(NOT Python_FOUND OR NOT pybind11_FOUND)
    message(FATAL_ERROR "RTCSIM_PYTHON needs python3-dev and pybind11-dev (scripts/setup installs them)")
  endif()
  set(CMAKE_POSITION_INDEPENDENT_CODE ON)
endif()
