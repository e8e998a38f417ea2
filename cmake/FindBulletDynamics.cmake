# FindBulletDynamics: Bullet's rigid-body dynamics (BulletDynamics, BulletCollision, LinearMath)
# from Debian 12's libbullet-dev (3.24), whose CMake config sets only relative paths and no
# targets. Defines Bullet::Dynamics. Debian builds Bullet in single precision (no
# BT_USE_DOUBLE_PRECISION), which is what its headers must be compiled with.
find_path(BulletDynamics_INCLUDE_DIR btBulletDynamicsCommon.h PATH_SUFFIXES bullet)
find_library(BulletDynamics_LIBRARY NAMES BulletDynamics)
find_library(BulletDynamics_COLLISION_LIBRARY NAMES BulletCollision)
find_library(BulletDynamics_MATH_LIBRARY NAMES LinearMath)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(BulletDynamics REQUIRED_VARS BulletDynamics_LIBRARY
  BulletDynamics_COLLISION_LIBRARY BulletDynamics_MATH_LIBRARY BulletDynamics_INCLUDE_DIR)
if(BulletDynamics_FOUND AND NOT TARGET Bullet::Dynamics)
  add_library(Bullet::Dynamics INTERFACE IMPORTED)
  set_target_properties(Bullet::Dynamics PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${BulletDynamics_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES
      "${BulletDynamics_LIBRARY};${BulletDynamics_COLLISION_LIBRARY};${BulletDynamics_MATH_LIBRARY}")
endif()
mark_as_advanced(BulletDynamics_INCLUDE_DIR BulletDynamics_LIBRARY BulletDynamics_COLLISION_LIBRARY
  BulletDynamics_MATH_LIBRARY)
