# Import through Assimp (issue 32): FBX and Collada as scenes, BVH motion onto a rig, against Blender's
# own posed meshes (../shared/data/rigged), and broken files refused by name.
dfm_test(test_assimp_scene_import SOURCES test_assimp_scene_import.cpp LIBS dfm_export dfm_scene)
target_compile_definitions(test_assimp_scene_import PRIVATE DFM_DEFORM_EXE="$<TARGET_FILE:deform>")
add_dependencies(test_assimp_scene_import deform)
