# FindMUMPS: the sequential (non-MPI) double-precision MUMPS as packaged by Debian
# (libmumps-seq-dev; headers from libmumps-headers-dev), which ships no CMake configuration.
# Defines the imported target MUMPS::MUMPS. Only the *_seq libraries are searched: the
# parallel libdmumps would need an MPI runtime and MPI_Init. The sequential build replaces MPI
# by libmpiseq, so dmumps_c.h needs no mpi.h. Being an imported target, its include directory
# reaches compilers as -isystem (no warnings from the MUMPS headers).
include(FindPackageHandleStandardArgs)
find_path(MUMPS_INCLUDE_DIR dmumps_c.h)
find_library(MUMPS_DMUMPS_LIBRARY dmumps_seq)
find_library(MUMPS_COMMON_LIBRARY mumps_common_seq)
find_library(MUMPS_MPISEQ_LIBRARY mpiseq_seq)
find_library(MUMPS_PORD_LIBRARY pord_seq)
find_package_handle_standard_args(MUMPS REQUIRED_VARS
  MUMPS_INCLUDE_DIR MUMPS_DMUMPS_LIBRARY MUMPS_COMMON_LIBRARY MUMPS_MPISEQ_LIBRARY
  MUMPS_PORD_LIBRARY)
if(MUMPS_FOUND AND NOT TARGET MUMPS::MUMPS)
  add_library(MUMPS::MUMPS UNKNOWN IMPORTED)
  set_target_properties(MUMPS::MUMPS PROPERTIES
    IMPORTED_LOCATION "${MUMPS_DMUMPS_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${MUMPS_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES
      "${MUMPS_COMMON_LIBRARY};${MUMPS_MPISEQ_LIBRARY};${MUMPS_PORD_LIBRARY}")
endif()
mark_as_advanced(MUMPS_INCLUDE_DIR MUMPS_DMUMPS_LIBRARY MUMPS_COMMON_LIBRARY
                 MUMPS_MPISEQ_LIBRARY MUMPS_PORD_LIBRARY)
