# dfm_module(NAME dir DEPS libs...): a static library from every .cpp in a folder.
# Each folder of core/ is one module so a half-edited neighbour does not break your target.
function(dfm_module name dir)
  cmake_parse_arguments(M "" "" "DEPS" ${ARGN})
  file(GLOB srcs CONFIGURE_DEPENDS ${dir}/*.cpp)
  if(NOT srcs)  # a module still being written: headers only
    add_library(${name} INTERFACE)
    target_include_directories(${name} INTERFACE ${PROJECT_SOURCE_DIR})
    target_link_libraries(${name} INTERFACE ${M_DEPS})
    return()
  endif()
  add_library(${name} STATIC ${srcs})
  target_include_directories(${name} PUBLIC ${PROJECT_SOURCE_DIR})
  target_link_libraries(${name} PUBLIC ${M_DEPS})
  dfm_module_pch(${name})
endfunction()

# cmake/module_pch.h precompiled once (dfm_module_pch) and reused by every core/, render/ and app/
# target's own sources: one compile instead of one per target (CI budget).
function(dfm_module_pch name)
  if(NOT TARGET dfm_module_pch)
    add_library(dfm_module_pch OBJECT ${PROJECT_SOURCE_DIR}/cmake/module_pch.cpp)
    target_link_libraries(dfm_module_pch PRIVATE Eigen3::Eigen)
    target_precompile_headers(dfm_module_pch PRIVATE ${PROJECT_SOURCE_DIR}/cmake/module_pch.h)
  endif()
  target_link_libraries(${name} PRIVATE Eigen3::Eigen)
  target_precompile_headers(${name} REUSE_FROM dfm_module_pch)
endfunction()

# dfm_test(NAME SOURCES files... LIBS libs... [GL] [TIMEOUT s]): one Catch2 executable = one ctest entry.
# GL tests need a display (the test command runs ctest under xvfb-run).
function(dfm_test name)
  cmake_parse_arguments(T "GL" "TIMEOUT" "SOURCES;LIBS" ${ARGN})
  add_executable(${name} ${T_SOURCES})
  target_link_libraries(${name} PRIVATE dfm_test_main ${T_LIBS})
  # tests/test_pch.h, compiled once (tests/CMakeLists.txt); sources from outside tests/ go without it.
  target_precompile_headers(${name} REUSE_FROM dfm_test_pch)
  foreach(src ${T_SOURCES})
    if(NOT src MATCHES "^test_" AND NOT src MATCHES "/tests/test_")
      set_source_files_properties(${src} PROPERTIES SKIP_PRECOMPILE_HEADERS ON)
    endif()
  endforeach()
  # A test that can bind sets the numerics up as the programs do (core/bind/numeric_setup.h).
  foreach(lib dfm_bind dfm_anim dfm_scene dfm_export dfm_core)
    if(lib IN_LIST T_LIBS)
      target_sources(${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests/numerics_setup.cpp)
      set_source_files_properties(${PROJECT_SOURCE_DIR}/tests/numerics_setup.cpp PROPERTIES SKIP_PRECOMPILE_HEADERS ON)
      break()
    endif()
  endforeach()
  target_compile_definitions(${name} PRIVATE DFM_DATA_DIR="${DFM_DATA_DIR}")
  if(DFM_SANITIZE)
    # Under the sanitizers (about 8x slower) a case tagged [heavy] is skipped: each one is a large-input
    # run of code that a lighter case of the same executable (or a named neighbour) covers there; the
    # release suite runs every case. ~[.] keeps hidden cases hidden (an exclusion-only spec selects them).
    add_test(NAME ${name} COMMAND ${name} "~[.]~[heavy]")
  else()
    add_test(NAME ${name} COMMAND ${name})
  endif()
  set(labels "")
  if(T_GL)
    list(APPEND labels gl)
  else()
    list(APPEND labels cpu)
  endif()
  if(NOT T_TIMEOUT)
    set(T_TIMEOUT 300)
  endif()
  set_tests_properties(${name} PROPERTIES LABELS "${labels}" TIMEOUT ${T_TIMEOUT}
    ENVIRONMENT "DFM_DATA_DIR=${DFM_DATA_DIR}")
endfunction()
