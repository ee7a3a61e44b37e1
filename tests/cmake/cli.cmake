# End-to-end tests of the `deform` executable (run as a child process). GL: `deform pose` without
# --cpu skins on the GPU when a display exists.
dfm_test(test_cli SOURCES test_cli.cpp LIBS dfm_core GL TIMEOUT 600)
target_compile_definitions(test_cli PRIVATE DEFORM_EXE="$<TARGET_FILE:deform>")
add_dependencies(test_cli deform)
