# Included by the top CMakeLists.txt before find_package(pybind11): chooses the interpreter the module is
# built for with CMake's FindPython, which puts pybind11 in its FindPython mode. Without it pybind11 runs
# the first python3.N found on PATH, and a pyenv shim for a version that is not installed fails the whole
# configure. Default: Debian's /usr/bin/python3 (the one with numpy and scipy); -DPython3_EXECUTABLE=...
# picks another. Without Python headers the module is skipped, the rest of the project still configures.
if(NOT DEFINED Python3_EXECUTABLE AND EXISTS /usr/bin/python3)
  set(Python3_EXECUTABLE /usr/bin/python3 CACHE FILEPATH "Python interpreter the iarap module is built for")
endif()
find_package(Python3 3.8 QUIET COMPONENTS Interpreter Development.Module)
if(NOT Python3_FOUND)
  set(PYBIND11_NOPYTHON ON)
endif()
