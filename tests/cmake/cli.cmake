# End-to-end tests of the `deform` executable (run as a child process). GL: `deform pose` without
# --cpu skins on the GPU when a display exists.
dfm_test(test_cli SOURCES test_cli.cpp LIBS dfm_core GL TIMEOUT 600)
target_compile_definitions(test_cli PRIVATE DEFORM_EXE="$<TARGET_FILE:deform>")
add_dependencies(test_cli deform)
# `deform manifold` over keyframes of any connectivity (prism build or transition), stage stats and
# hostile keyframes.
dfm_test(test_cli_key_mesh SOURCES test_cli_key_mesh.cpp LIBS dfm_anim dfm_mesh TIMEOUT 600)
target_compile_definitions(test_cli_key_mesh PRIVATE DEFORM_EXE="$<TARGET_FILE:deform>")
add_dependencies(test_cli_key_mesh deform)
