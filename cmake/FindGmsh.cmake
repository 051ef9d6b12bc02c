# FindGmsh: the Gmsh library and its C++ API (gmsh.h) as packaged by Debian (libgmsh-dev),
# which ships no CMake configuration. Defines the imported target Gmsh::Gmsh and Gmsh_VERSION
# (from GMSH_API_VERSION in gmsh.h). Being an imported target, its include directory reaches
# compilers as -isystem (no warnings from gmsh.h).
include(FindPackageHandleStandardArgs)
find_path(Gmsh_INCLUDE_DIR gmsh.h)
find_library(Gmsh_LIBRARY NAMES gmsh)
if(Gmsh_INCLUDE_DIR AND EXISTS "${Gmsh_INCLUDE_DIR}/gmsh.h")
  file(STRINGS "${Gmsh_INCLUDE_DIR}/gmsh.h" _gmsh_version_line
       REGEX "^#define GMSH_API_VERSION \"[0-9.]+\"")
  string(REGEX REPLACE ".*\"([0-9.]+)\".*" "\\1" Gmsh_VERSION "${_gmsh_version_line}")
  unset(_gmsh_version_line)
endif()
find_package_handle_standard_args(Gmsh
  REQUIRED_VARS Gmsh_LIBRARY Gmsh_INCLUDE_DIR
  VERSION_VAR Gmsh_VERSION)
if(Gmsh_FOUND AND NOT TARGET Gmsh::Gmsh)
  add_library(Gmsh::Gmsh UNKNOWN IMPORTED)
  set_target_properties(Gmsh::Gmsh PROPERTIES
    IMPORTED_LOCATION "${Gmsh_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${Gmsh_INCLUDE_DIR}")
endif()
mark_as_advanced(Gmsh_INCLUDE_DIR Gmsh_LIBRARY)
