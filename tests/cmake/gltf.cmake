# glTF export (core/export): unit and round-trip tests, and the Khronos validator run (Node.js).
dfm_test(test_gltf SOURCES test_gltf.cpp LIBS dfm_export)
# Installs tests/gltf's pinned gltf-validator with npm on first run (needs the npm registry).
dfm_test(test_gltf_validator SOURCES test_gltf_validator.cpp LIBS dfm_export nlohmann_json::nlohmann_json TIMEOUT 600)
target_compile_definitions(test_gltf_validator PRIVATE DFM_GLTF_VALIDATOR_DIR="${CMAKE_CURRENT_SOURCE_DIR}/gltf")
# The shared data sets and assets/ scenes (the default scene is bound here: tens of seconds):
# validator + round trip (reads ../shared/data), and `deform export SCENE` end to end.
dfm_test(test_gltf_data SOURCES test_gltf_data.cpp LIBS dfm_export dfm_scene dfm_bind nlohmann_json::nlohmann_json TIMEOUT 1500)
target_compile_definitions(test_gltf_data PRIVATE DFM_GLTF_VALIDATOR_DIR="${CMAKE_CURRENT_SOURCE_DIR}/gltf"
                           DFM_SOURCE_DIR="${PROJECT_SOURCE_DIR}" DFM_DEFORM_EXE="$<TARGET_FILE:deform>")
add_dependencies(test_gltf_data deform)
# Import: a rigged, animated glTF file as a scene, against Blender's own posed meshes (../shared/data/rigged).
dfm_test(test_gltf_scene_import SOURCES test_gltf_scene_import.cpp LIBS dfm_export dfm_scene)
target_compile_definitions(test_gltf_scene_import PRIVATE DFM_DEFORM_EXE="$<TARGET_FILE:deform>" DFM_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
add_dependencies(test_gltf_scene_import deform)
# CUBICSPLINE curves: the reader's Hermite sampling and the import's keys along the curve.
dfm_test(test_gltf_cubic SOURCES test_gltf_cubic.cpp LIBS dfm_export dfm_scene)
