# FindLibsumo: SUMO in-process (libsumocpp) from Debian 12's sumo package (1.15), which ships the
# library and its headers (/usr/include/libsumo) but no CMake config. Defines Libsumo::Libsumo.
find_path(Libsumo_INCLUDE_DIR libsumo/libsumo.h)
find_library(Libsumo_LIBRARY NAMES sumocpp)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(Libsumo REQUIRED_VARS Libsumo_LIBRARY Libsumo_INCLUDE_DIR)
if(Libsumo_FOUND AND NOT TARGET Libsumo::Libsumo)
  add_library(Libsumo::Libsumo UNKNOWN IMPORTED)
  set_target_properties(Libsumo::Libsumo PROPERTIES
    IMPORTED_LOCATION "${Libsumo_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${Libsumo_INCLUDE_DIR}")
endif()
mark_as_advanced(Libsumo_INCLUDE_DIR Libsumo_LIBRARY)
