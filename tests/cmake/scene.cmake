# core/scene: the document, its file format, the script language and the default scene generator.
dfm_test(test_document SOURCES test_document.cpp LIBS dfm_scene)
dfm_test(test_scene_file SOURCES test_scene_file.cpp LIBS dfm_scene)
dfm_test(test_script SOURCES test_script.cpp LIBS dfm_scene)
target_compile_definitions(test_script PRIVATE DFM_ASSETS_DIR="${PROJECT_SOURCE_DIR}/assets")
# Mesh keys: the document command, hostile files, the script's key-mesh, key_surfaces -> manifold.
dfm_test(test_key_mesh SOURCES test_key_mesh.cpp LIBS dfm_scene)

# The generator of assets/default.* (run by hand: make_default_scene assets). Built with the tests so
# the test below can regenerate the scene and compare it with the committed copy.
add_executable(make_default_scene ${PROJECT_SOURCE_DIR}/tools/make_default_scene.cpp)
target_link_libraries(make_default_scene PRIVATE dfm_scene)
dfm_test(test_scene_default SOURCES test_scene_default.cpp LIBS dfm_scene)
add_dependencies(test_scene_default make_default_scene)
target_compile_definitions(test_scene_default PRIVATE DFM_ASSETS_DIR="${PROJECT_SOURCE_DIR}/assets"
  DFM_MAKE_DEFAULT_SCENE="$<TARGET_FILE:make_default_scene>")
# Posing by dragging (FAST) through the document and the script.
dfm_test(test_posing SOURCES test_posing.cpp LIBS dfm_scene dfm_export)
target_compile_definitions(test_posing PRIVATE DFM_ASSETS_DIR="${PROJECT_SOURCE_DIR}/assets")
# Dynamics in the document: live drags, simulate, the settings in the scene file.
dfm_test(test_dynamics_posing SOURCES test_dynamics_posing.cpp LIBS dfm_scene dfm_export)
target_compile_definitions(test_dynamics_posing PRIVATE DFM_ASSETS_DIR="${PROJECT_SOURCE_DIR}/assets")
# The command table: a script line and a UI call give the same document; SCRIPT.md lists the table.
dfm_test(test_commands SOURCES test_commands.cpp LIBS dfm_scene)
target_compile_definitions(test_commands PRIVATE DFM_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
# Twist and stretch an artist can reach (issue 33): the commands, the stretch's closed form, keys that carry them.
dfm_test(test_twist_stretch_script SOURCES test_twist_stretch_script.cpp LIBS dfm_scene)
target_compile_definitions(test_twist_stretch_script PRIVATE DFM_DEFORM_EXE="$<TARGET_FILE:deform>")
add_dependencies(test_twist_stretch_script deform)
# The script's transfer-weights (issue 34): a scene's or a mesh's weights onto the document's surface.
dfm_test(test_transfer_weights_script SOURCES test_transfer_weights_script.cpp LIBS dfm_scene)
target_compile_definitions(test_transfer_weights_script PRIVATE DFM_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
# Space-time edits (issue 35): edit-region / edit-drag, the scene round trip, undo, hostile input.
dfm_test(test_space_time_script SOURCES test_space_time_script.cpp LIBS dfm_scene)
# Additional weights (Jacobson 2013, 7.3.3) in the document's bind, FAST, skinning and scene file.
dfm_test(test_additional_weights_document SOURCES test_additional_weights_document.cpp LIBS dfm_scene)
