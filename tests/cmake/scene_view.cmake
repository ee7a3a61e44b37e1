# The editor's viewport logic (app/editor/scene_view) against a recording mock of render/backend.h:
# built from its sources with core/ only, no GL library and no context.
dfm_test(test_scene_view SOURCES test_scene_view.cpp ${PROJECT_SOURCE_DIR}/app/editor/scene_view.cpp
         ${PROJECT_SOURCE_DIR}/app/editor/scene_overlays.cpp
         ${PROJECT_SOURCE_DIR}/app/editor/slice_cache.cpp ${PROJECT_SOURCE_DIR}/app/editor/interval_prefetch.cpp
         ${PROJECT_SOURCE_DIR}/app/editor/manifold_builder.cpp ${PROJECT_SOURCE_DIR}/app/editor/view_model.cpp
         ${PROJECT_SOURCE_DIR}/app/editor/pose_tool.cpp ${PROJECT_SOURCE_DIR}/app/editor/gizmo.cpp
         ${PROJECT_SOURCE_DIR}/app/editor/paint_tool.cpp ${PROJECT_SOURCE_DIR}/app/editor/sculpt_tool.cpp
         ${PROJECT_SOURCE_DIR}/app/editor/space_time_tool.cpp
         ${PROJECT_SOURCE_DIR}/render/overlay_geometry.cpp ${PROJECT_SOURCE_DIR}/render/interval_records.cpp
         LIBS dfm_core imgui)
