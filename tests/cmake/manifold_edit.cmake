# Space-time Laplacian editing of animation manifolds (issue 35; Southern 2008 ch. 4).
dfm_test(test_manifold_edit SOURCES test_manifold_edit.cpp LIBS dfm_anim dfm_mesh)
# `deform edit-manifold`: the written edit, printed times, hostile input.
dfm_test(test_cli_edit_manifold SOURCES test_cli_edit_manifold.cpp LIBS dfm_anim TIMEOUT 300)
target_compile_definitions(test_cli_edit_manifold PRIVATE DEFORM_EXE="$<TARGET_FILE:deform>")
add_dependencies(test_cli_edit_manifold deform)
# Edge splits and space-time edits that refine what they stretch (Southern 4.5.1).
dfm_test(test_manifold_refine SOURCES test_manifold_refine.cpp LIBS dfm_anim dfm_mesh)
