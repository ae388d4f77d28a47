# Run at each build (cmake -P, from app/CMakeLists.txt): writes OUT_DIR/BonelessVersion.h, and
# BonelessVersion.txt for cpack, only when the version changed, so that a build of the same
# commit compiles nothing again and a `git pull` needs no new configure.
include(${CMAKE_CURRENT_LIST_DIR}/GitVersion.cmake)
boneless_version(version "${SOURCE_DIR}" "${VERSION}")
set(header "#pragma once\n#define BONELESS_VERSION \"${version}\"\n")
if(EXISTS "${OUT_DIR}/BonelessVersion.h")
  file(READ "${OUT_DIR}/BonelessVersion.h" old)
endif()
if(NOT old STREQUAL header OR NOT EXISTS "${OUT_DIR}/BonelessVersion.txt")
  file(WRITE "${OUT_DIR}/BonelessVersion.h" "${header}")
  file(WRITE "${OUT_DIR}/BonelessVersion.txt" "${version}")
endif()
