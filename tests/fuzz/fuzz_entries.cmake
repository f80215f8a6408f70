# The fuzz entry points as a library: used by the libFuzzer targets (tests/fuzz, Q3MAP_FUZZ builds)
# and by the regression test (tests/fuzz_regressions, normal test builds). Included from both.
if(NOT TARGET q3fuzz_entries)
  # The small consistent BSP of the bspfile tests, built here too because tests/ is off in fuzz builds.
  add_library(q3fuzz_synthetic STATIC ${PROJECT_SOURCE_DIR}/tests/bspfile/synthetic_bsp.cpp)
  target_include_directories(q3fuzz_synthetic PUBLIC ${PROJECT_SOURCE_DIR}/tests/bspfile)
  target_link_libraries(q3fuzz_synthetic PUBLIC q3bspfile q3sh)

  add_library(q3fuzz_entries STATIC
    ${CMAKE_CURRENT_LIST_DIR}/fuzz_entries.cpp
    ${CMAKE_CURRENT_LIST_DIR}/fuzz_entries_bsp.cpp
    ${CMAKE_CURRENT_LIST_DIR}/fuzz_entries_text.cpp
    ${CMAKE_CURRENT_LIST_DIR}/fuzz_entries_files.cpp
    ${CMAKE_CURRENT_LIST_DIR}/fuzz_entries_prt.cpp)
  target_include_directories(q3fuzz_entries PUBLIC ${CMAKE_CURRENT_LIST_DIR})
  target_link_libraries(q3fuzz_entries PUBLIC q3fuzz_synthetic q3bspfile q3sh q3mapfile q3shaders q3json q3vfs q3vis
                        q3io q3log q3script)
endif()
