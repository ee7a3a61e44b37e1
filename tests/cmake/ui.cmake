# What the panels show, as plain data (app/editor/view_model): layout, labels, the in-between of a
# transition interval, the rig's fade over other meshes.
dfm_test(test_editor_view_model SOURCES test_editor_view_model.cpp ${PROJECT_SOURCE_DIR}/app/editor/view_model.cpp
         LIBS dfm_core)
# The editor's CPU logic: camera and picking (core/view), and the gizmo, built from its sources so a
# half-written GL pass in render/ never blocks these tests.
dfm_test(test_camera SOURCES test_camera.cpp LIBS dfm_view)
dfm_test(test_view_color SOURCES test_view_color.cpp LIBS dfm_view)
dfm_test(test_editor_picking SOURCES test_editor_picking.cpp LIBS dfm_view)
dfm_test(test_editor_gizmo SOURCES test_editor_gizmo.cpp
         ${PROJECT_SOURCE_DIR}/app/editor/gizmo.cpp ${PROJECT_SOURCE_DIR}/app/editor/camera_sync.cpp
         ${PROJECT_SOURCE_DIR}/app/editor/file_panel.cpp ${PROJECT_SOURCE_DIR}/render/overlay_geometry.cpp
         LIBS dfm_view imgui)

# The real editor binary under the suite's X server.
if(DFM_BUILD_EDITOR)
  dfm_test(test_editor_gl GL SOURCES test_editor_gl.cpp ${PROJECT_SOURCE_DIR}/render/screenshot.cpp
           LIBS dfm_util PkgConfig::EPOXY TIMEOUT 600)
  target_compile_definitions(test_editor_gl PRIVATE DFM_EDITOR_EXE="$<TARGET_FILE:deform-editor>")
  add_dependencies(test_editor_gl deform-editor)
endif()

# The editor's bind job (worker thread, same core call as the CLI, painted mask) without a window.
dfm_test(test_editor_bind SOURCES test_editor_bind.cpp ${PROJECT_SOURCE_DIR}/app/editor/bind_job.cpp
         ${PROJECT_SOURCE_DIR}/app/editor/bind_worker.cpp LIBS dfm_scene TIMEOUT 300)

# The editor loop's pacing (idle sleeps, 30 Hz while a job runs) and the HUD's frame figures.
dfm_test(test_editor_pacing SOURCES test_editor_pacing.cpp ${PROJECT_SOURCE_DIR}/app/editor/frame_pacing.cpp)
# Picked pairs (issue 30): the key-pair command, the scene file, the editor's Pair tool (app/editor/pair_tool).
dfm_test(test_key_pairs SOURCES test_key_pairs.cpp ${PROJECT_SOURCE_DIR}/app/editor/pair_tool.cpp LIBS dfm_core)
# The Select tool's rest-pose drag of handles and joints (app/editor/rig_drag), without a window.
dfm_test(test_rig_drag SOURCES test_rig_drag.cpp ${PROJECT_SOURCE_DIR}/app/editor/rig_drag.cpp LIBS dfm_core)
