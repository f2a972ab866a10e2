# S. G. Johnson's cubature (Debian's libcubature-dev): a plain C library with neither a CMake
# package nor a pkg-config file, found by its header and library as the target cubature::cubature.
# Included by the build and by the installed package (sedwaveConfig.cmake).
if(NOT TARGET cubature::cubature)
  find_path(CUBATURE_INCLUDE_DIR cubature.h REQUIRED)
  find_library(CUBATURE_LIBRARY cubature REQUIRED)
  add_library(cubature::cubature UNKNOWN IMPORTED)
  set_target_properties(cubature::cubature PROPERTIES IMPORTED_LOCATION "${CUBATURE_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${CUBATURE_INCLUDE_DIR}")
endif()
