# Shape spaces from morphing (Alexa 2002, ch. 5): synthesis by Eq. 5.31's chain, linear analysis, the pad.
dfm_test(test_shape_space SOURCES test_shape_space.cpp LIBS dfm_anim dfm_mesh)
# `deform shape-space` end to end (synthesis, analysis, exit codes).
dfm_test(test_shape_space_cli SOURCES test_shape_space_cli.cpp LIBS dfm_mesh)
target_compile_definitions(test_shape_space_cli PRIVATE DEFORM_EXE="$<TARGET_FILE:deform>")
add_dependencies(test_shape_space_cli deform)
# The script's shape-space-key over the document's keys (core/scene/shape_space_keys).
dfm_test(test_shape_space_script SOURCES test_shape_space_script.cpp LIBS dfm_scene)
