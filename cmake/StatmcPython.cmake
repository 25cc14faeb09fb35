# Finds what the Python module needs (Debian: pybind11-dev, python3-dev, python3-numpy) and
# adds python/. STATMC_PYTHON=AUTO builds it when found, ON requires it, OFF skips it.
# Fuzzing builds never do: libFuzzer's runtime cannot be loaded into python3.
set(STATMC_PYTHON_MODULE OFF)
if(NOT STATMC_PYTHON STREQUAL "OFF" AND NOT STATMC_FUZZ)
  # Debian's interpreter, whose numpy and OpenImageIO bindings are installed, rather than
  # whatever python3 comes first on PATH (a pyenv shim has neither).
  # -DPython3_EXECUTABLE= (FindPython3's spelling) names the interpreter too.
  if(NOT DEFINED Python_EXECUTABLE AND DEFINED Python3_EXECUTABLE)
    set(Python_EXECUTABLE ${Python3_EXECUTABLE})
  endif()
  if(NOT DEFINED Python_EXECUTABLE AND EXISTS /usr/bin/python3)
    set(Python_EXECUTABLE /usr/bin/python3)
  endif()
  find_package(Python 3 COMPONENTS Interpreter Development.Module)
  set(PYBIND11_FINDPYTHON ON)
  find_package(pybind11 CONFIG QUIET)
  if(Python_FOUND AND pybind11_FOUND)
    set(STATMC_PYTHON_MODULE ON)
    add_subdirectory(python)
  elseif(STATMC_PYTHON STREQUAL "ON")
    message(FATAL_ERROR "STATMC_PYTHON=ON needs pybind11-dev and python3-dev")
  else()
    message(STATUS "statmc: no Python module (install pybind11-dev and python3-dev)")
  endif()
endif()
