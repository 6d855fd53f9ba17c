# Where the Python package goes in an installed prefix, relative to it:
# lib/python3.X/dist-packages for Debian's interpreter (on its sys.path for the prefix /usr/local),
# lib/python3.X/site-packages for others. Override with -DVGROOVE_PYTHON_INSTALL_DIR=...
if(Python3_Interpreter_FOUND)
  execute_process(
    COMMAND ${Python3_EXECUTABLE} -c
            "import sys; print('dist-packages' if any(p.endswith('dist-packages') for p in sys.path) else 'site-packages')"
    OUTPUT_VARIABLE _vgroove_site OUTPUT_STRIP_TRAILING_WHITESPACE)
  set(_vgroove_pydir lib/python${Python3_VERSION_MAJOR}.${Python3_VERSION_MINOR}/${_vgroove_site})
else()
  set(_vgroove_pydir lib/python3/dist-packages)
endif()
set(VGROOVE_PYTHON_INSTALL_DIR ${_vgroove_pydir} CACHE STRING
    "Python package directory, relative to the install prefix")
# The package in the build tree: PYTHONPATH=build/python.
set(VGROOVE_PYTHON_BUILD_DIR ${CMAKE_BINARY_DIR}/python)
