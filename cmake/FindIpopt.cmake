# FindIpopt: the COIN-OR Ipopt interior-point optimiser as packaged by Debian
# (coinor-libipopt-dev), which ships a pkg-config file but no CMake configuration.
# Defines the imported target Ipopt::Ipopt (include directories, compile definitions such as
# HAVE_CSTDDEF, and the link line with MUMPS/LAPACK as given by ipopt.pc) and Ipopt_VERSION.
include(FindPackageHandleStandardArgs)
find_package(PkgConfig QUIET)
if(PKG_CONFIG_FOUND)
  pkg_check_modules(IPOPT QUIET IMPORTED_TARGET ipopt)
endif()
find_package_handle_standard_args(Ipopt
  REQUIRED_VARS IPOPT_LINK_LIBRARIES IPOPT_FOUND
  VERSION_VAR IPOPT_VERSION)
if(Ipopt_FOUND AND NOT TARGET Ipopt::Ipopt)
  # An interface wrapper rather than an ALIAS: aliases of non-global imported targets are not
  # allowed, and the namespaced name matches the other dependencies (CHOLMOD::CHOLMOD).
  add_library(Ipopt::Ipopt INTERFACE IMPORTED)
  target_link_libraries(Ipopt::Ipopt INTERFACE PkgConfig::IPOPT)
  set(Ipopt_VERSION "${IPOPT_VERSION}")
endif()
