# FindCHOLMOD: SuiteSparse's CHOLMOD as packaged by Debian (libsuitesparse-dev), which ships
# no CMake configuration. Defines the imported target CHOLMOD::CHOLMOD, carrying the
# libraries CHOLMOD's supernodal factorisation and METIS ordering need. Being an imported
# target, its include directory reaches compilers as -isystem (no warnings from cholmod.h).
include(FindPackageHandleStandardArgs)
find_path(CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse)
find_library(CHOLMOD_LIBRARY cholmod)
find_library(SUITESPARSE_CONFIG_LIBRARY suitesparseconfig)
find_library(CHOLMOD_AMD_LIBRARY amd)
find_library(CHOLMOD_COLAMD_LIBRARY colamd)
find_library(CHOLMOD_METIS_LIBRARY metis)
find_package_handle_standard_args(CHOLMOD REQUIRED_VARS
  CHOLMOD_INCLUDE_DIR CHOLMOD_LIBRARY SUITESPARSE_CONFIG_LIBRARY CHOLMOD_AMD_LIBRARY
  CHOLMOD_COLAMD_LIBRARY CHOLMOD_METIS_LIBRARY)
if(CHOLMOD_FOUND AND NOT TARGET CHOLMOD::CHOLMOD)
  add_library(CHOLMOD::CHOLMOD UNKNOWN IMPORTED)
  set_target_properties(CHOLMOD::CHOLMOD PROPERTIES
    IMPORTED_LOCATION "${CHOLMOD_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${CHOLMOD_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES
      "${SUITESPARSE_CONFIG_LIBRARY};${CHOLMOD_AMD_LIBRARY};${CHOLMOD_COLAMD_LIBRARY};${CHOLMOD_METIS_LIBRARY}")
endif()
mark_as_advanced(CHOLMOD_INCLUDE_DIR CHOLMOD_LIBRARY SUITESPARSE_CONFIG_LIBRARY
                 CHOLMOD_AMD_LIBRARY CHOLMOD_COLAMD_LIBRARY CHOLMOD_METIS_LIBRARY)
