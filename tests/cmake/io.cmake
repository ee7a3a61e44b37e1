# io engineer: readers/writers, mesh checks, rig files, fuzzing.
dfm_test(test_io_data SOURCES test_io_data.cpp LIBS dfm_rig)
dfm_test(test_io_roundtrip SOURCES test_io_roundtrip.cpp LIBS dfm_rig)
dfm_test(test_io_hostile SOURCES test_io_hostile.cpp LIBS dfm_mesh dfm_scene)
dfm_test(test_mesh_info SOURCES test_mesh_info.cpp LIBS dfm_mesh)
dfm_test(test_io_fuzz_inputs SOURCES test_io_fuzz_inputs.cpp LIBS dfm_rig dfm_scene dfm_export)
target_compile_definitions(test_io_fuzz_inputs PRIVATE DFM_FUZZ_DIR="${CMAKE_CURRENT_SOURCE_DIR}/fuzz")
# Saves that fail (full disk, permission denied) keep the previous file: OBJ, PLY, dmat, scene.
dfm_test(test_io_save SOURCES test_io_save.cpp LIBS dfm_scene dfm_mesh)
if(DFM_FUZZ)
  include(${CMAKE_CURRENT_SOURCE_DIR}/fuzz/CMakeLists.txt)
endif()

# `deform info` on every shared data file must succeed; on a bad file it must exit 1 naming the file.
file(GLOB dfm_io_data_files ${DFM_DATA_DIR}/*.obj ${DFM_DATA_DIR}/*.off ${DFM_DATA_DIR}/*.mesh
     ${DFM_DATA_DIR}/*.tgf ${DFM_DATA_DIR}/*.dmat)
if(dfm_io_data_files)
  add_test(NAME cli_info_data COMMAND deform info ${dfm_io_data_files})
  set_tests_properties(cli_info_data PROPERTIES LABELS cpu TIMEOUT 120)
endif()
add_test(NAME cli_info_bad_file
  COMMAND sh -c "out=$(\"$0\" info \"$1\" 2>&1); code=$?; echo \"$out\"; [ $code -eq 1 ] && echo \"$out\" | grep -q 'bad.off:2: vertex count'"
          $<TARGET_FILE:deform> ${CMAKE_CURRENT_SOURCE_DIR}/hostile/bad.off)
set_tests_properties(cli_info_bad_file PROPERTIES LABELS cpu TIMEOUT 60)
