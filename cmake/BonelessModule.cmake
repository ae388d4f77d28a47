# boneless_add_module(<name> [DEPENDS <module>...] [PUBLIC_LIBS <lib>...] [PRIVATE_LIBS <lib>...])
#
# One core module: the static library boneless_<name> from core/<name>/src, its public headers in
# core/<name>/include/boneless, and boneless_<name>_internal, which adds the private headers of
# core/<name>/src for the tests and benchmarks that check private pieces (never for ui/ or app/).
# A module sees only the modules it names in DEPENDS (which must be
# declared before it, so the order is a DAG), never Qt or VTK, and the configure step fails when a
# source includes a header of a module it does not depend on.
function(boneless_add_module name)
  cmake_parse_arguments(ARG "" "" "DEPENDS;PUBLIC_LIBS;PRIVATE_LIBS" ${ARGN})
  set(dir ${CMAKE_CURRENT_SOURCE_DIR})
  file(GLOB sources CONFIGURE_DEPENDS ${dir}/src/*.cpp)
  file(GLOB headers CONFIGURE_DEPENDS ${dir}/include/boneless/*.h ${dir}/src/*.h)
  add_library(boneless_${name} STATIC ${sources} ${headers})
  target_include_directories(boneless_${name} PUBLIC ${dir}/include PRIVATE ${dir}/src)
  set(deps)
  foreach(dep IN LISTS ARG_DEPENDS)
    if(NOT TARGET boneless_${dep})
      message(FATAL_ERROR "core module ${name} depends on ${dep}, which is not declared before it")
    endif()
    list(APPEND deps boneless_${dep})
  endforeach()
  target_link_libraries(boneless_${name} PUBLIC ${deps} ${ARG_PUBLIC_LIBS} PRIVATE ${ARG_PRIVATE_LIBS})
  target_compile_options(boneless_${name} PRIVATE -Wall -Wextra -Wno-unused-parameter
    # Eigen's vectorised kernels are the solver's inner loops; kept private so it never leaks.
    $<$<CONFIG:Release>:-march=x86-64-v2>)

  # The headers this module may include: its own and those of the modules it depends on.
  set(allowed)
  foreach(module IN ITEMS ${name} ${ARG_DEPENDS})
    file(GLOB visible RELATIVE ${CMAKE_CURRENT_SOURCE_DIR}/../${module}/include
         ${CMAKE_CURRENT_SOURCE_DIR}/../${module}/include/boneless/*.h)
    list(APPEND allowed ${visible})
  endforeach()
  foreach(file IN LISTS sources headers)
    file(STRINGS ${file} includes REGEX "^[ \t]*#[ \t]*include[ \t]*\"boneless/")
    foreach(line IN LISTS includes)
      string(REGEX REPLACE ".*\"(boneless/[^\"]+)\".*" "\\1" header "${line}")
      if(NOT header IN_LIST allowed)
        message(FATAL_ERROR "${file} includes ${header}, which is not in module ${name} "
                            "or in a module it depends on (${ARG_DEPENDS})")
      endif()
    endforeach()
  endforeach()
  boneless_forbid_dependencies(boneless_${name} PATTERNS "Qt" "VTK" "vtk" "boneless_ui"
    HEADERS "[<\"](Q[A-Z][A-Za-z]*|Qt[A-Za-z]*/|vtk[A-Za-z0-9_]*\\.h|boneless/ui/)")
  set_property(GLOBAL APPEND PROPERTY BONELESS_CORE_MODULES boneless_${name})

  add_library(boneless_${name}_internal INTERFACE)
  target_include_directories(boneless_${name}_internal INTERFACE ${dir}/src)
  target_link_libraries(boneless_${name}_internal INTERFACE boneless_${name})
  set_property(GLOBAL APPEND PROPERTY BONELESS_CORE_INTERNALS boneless_${name}_internal)
endfunction()
