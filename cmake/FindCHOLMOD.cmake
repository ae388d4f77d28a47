# Debian bookworm's SuiteSparse 5.12 ships no CMake config; this finds CHOLMOD and the
# SuiteSparse libraries it needs and provides the imported target CHOLMOD::CHOLMOD.
find_path(CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse)
find_library(CHOLMOD_LIBRARY cholmod)
find_library(SUITESPARSE_CONFIG_LIBRARY suitesparseconfig)
foreach(part amd camd colamd ccolamd)
  string(TOUPPER ${part} PART)
  find_library(${PART}_LIBRARY ${part})
  list(APPEND CHOLMOD_EXTRA_LIBRARIES ${${PART}_LIBRARY})
endforeach()
find_package(BLAS)
find_package(LAPACK)

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(CHOLMOD
  REQUIRED_VARS CHOLMOD_LIBRARY CHOLMOD_INCLUDE_DIR SUITESPARSE_CONFIG_LIBRARY)

if(CHOLMOD_FOUND AND NOT TARGET CHOLMOD::CHOLMOD)
  add_library(CHOLMOD::CHOLMOD UNKNOWN IMPORTED)
  set_target_properties(CHOLMOD::CHOLMOD PROPERTIES
    IMPORTED_LOCATION "${CHOLMOD_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${CHOLMOD_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES
      "${CHOLMOD_EXTRA_LIBRARIES};${SUITESPARSE_CONFIG_LIBRARY};${LAPACK_LIBRARIES};${BLAS_LIBRARIES}")
endif()
mark_as_advanced(CHOLMOD_INCLUDE_DIR CHOLMOD_LIBRARY SUITESPARSE_CONFIG_LIBRARY)
