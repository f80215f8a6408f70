# The fuzz entry points as a library: used by the libFuzzer targets (tests/fuzz, Q3MAP_FUZZ builds)
# and by the regression test (tests/fuzz_regressions, normal test builds). Included from both.
if(NOT TARGET q3fuzz_entries)
  # The small consistent BSP of the bspfile tests, built here too because tests/ is off in fuzz builds.
  add_library(q3fuzz_synthetic STATIC ${PROJECT_SOURCE_DIR}/tests/bspfile/synthetic_bsp.cpp)
  target_include_directories(q3fuzz_synthetic PUBLIC ${PROJECT_SOURCE_DIR}/tests/bspfile)
  target_link_libraries(q3fuzz_synthetic PUBLIC q3bspfile q3sh)

  # The light cache tests' hand-written BSP images (seeds of the lightcache target).
  add_library(q3fuzz_light_cache_maps STATIC ${PROJECT_SOURCE_DIR}/tests/sh/light_cache_test_bsp.cpp
              ${PROJECT_SOURCE_DIR}/tests/sh/sh_test_support.cpp)
  target_include_directories(q3fuzz_light_cache_maps PUBLIC ${PROJECT_SOURCE_DIR}/tests/sh)
  target_link_libraries(q3fuzz_light_cache_maps PUBLIC q3sh)

  # -bsp and -vis each have a portal_file.h, so the map_bsp entry (with -bsp's headers) and the
  # check that -vis reads its portal file (with -vis's) are libraries of their own.
  add_library(q3fuzz_prt_check STATIC ${CMAKE_CURRENT_LIST_DIR}/fuzz_prt_check.cpp)
  target_include_directories(q3fuzz_prt_check PUBLIC ${CMAKE_CURRENT_LIST_DIR})
  target_link_libraries(q3fuzz_prt_check PUBLIC q3bspfile PRIVATE q3vis)
  add_library(q3fuzz_map_bsp STATIC ${CMAKE_CURRENT_LIST_DIR}/fuzz_entries_map_bsp.cpp)
  target_include_directories(q3fuzz_map_bsp PUBLIC ${CMAKE_CURRENT_LIST_DIR})
  target_link_libraries(q3fuzz_map_bsp PUBLIC q3bspfile PRIVATE q3fuzz_prt_check q3bsp q3shaders q3mapfile q3log q3script)

  add_library(q3fuzz_entries STATIC
    ${CMAKE_CURRENT_LIST_DIR}/fuzz_entries.cpp
    ${CMAKE_CURRENT_LIST_DIR}/fuzz_entries_bsp.cpp
    ${CMAKE_CURRENT_LIST_DIR}/fuzz_entries_text.cpp
    ${CMAKE_CURRENT_LIST_DIR}/fuzz_entries_files.cpp
    ${CMAKE_CURRENT_LIST_DIR}/fuzz_entries_prt.cpp
    ${CMAKE_CURRENT_LIST_DIR}/fuzz_entries_world_lights.cpp
    ${CMAKE_CURRENT_LIST_DIR}/fuzz_entries_light_cache.cpp)
  target_include_directories(q3fuzz_entries PUBLIC ${CMAKE_CURRENT_LIST_DIR})
  target_link_libraries(q3fuzz_entries PUBLIC q3fuzz_synthetic q3fuzz_light_cache_maps q3bspfile q3sh q3mapfile q3shaders q3json q3vfs q3vis
                        q3io q3log q3script PRIVATE q3fuzz_map_bsp)
endif()
