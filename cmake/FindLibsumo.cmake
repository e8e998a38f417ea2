# FindLibsumo: SUMO's C++ client libraries from Debian 12's sumo package (1.15), which ships them
# and their headers (/usr/include/libsumo) but no CMake config. Defines Libsumo::Libsumo (SUMO in
# this process, libsumocpp) and Libsumo::Libtraci (a TraCI client of a separate SUMO process,
# libtracicpp; the same headers with LIBTRACI defined).
find_path(Libsumo_INCLUDE_DIR libsumo/libsumo.h)
find_library(Libsumo_LIBRARY NAMES sumocpp)
find_library(Libsumo_TRACI_LIBRARY NAMES tracicpp)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(Libsumo REQUIRED_VARS Libsumo_LIBRARY Libsumo_TRACI_LIBRARY Libsumo_INCLUDE_DIR)
if(Libsumo_FOUND AND NOT TARGET Libsumo::Libsumo)
  add_library(Libsumo::Libsumo UNKNOWN IMPORTED)
  set_target_properties(Libsumo::Libsumo PROPERTIES
    IMPORTED_LOCATION "${Libsumo_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${Libsumo_INCLUDE_DIR}")
  add_library(Libsumo::Libtraci UNKNOWN IMPORTED)
  set_target_properties(Libsumo::Libtraci PROPERTIES
    IMPORTED_LOCATION "${Libsumo_TRACI_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${Libsumo_INCLUDE_DIR}")
endif()
mark_as_advanced(Libsumo_INCLUDE_DIR Libsumo_LIBRARY Libsumo_TRACI_LIBRARY)
