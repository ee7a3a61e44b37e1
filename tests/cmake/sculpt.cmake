# Shape keys made here (issue 37): variational region deformation (Jacobson 2013 ch. 3), local
# transitions in Laplacian coordinates (Alexa 2002, 4.3), and the CLI commands that run them.
dfm_test(test_variational_deform SOURCES test_variational_deform.cpp LIBS dfm_sculpt)
dfm_test(test_differential_blend SOURCES test_differential_blend.cpp LIBS dfm_sculpt)
# `deform sculpt` and `deform interpolate --method differential` run as a child process.
dfm_test(test_cli_sculpt SOURCES test_cli_sculpt.cpp LIBS dfm_mesh TIMEOUT 120)
target_compile_definitions(test_cli_sculpt PRIVATE DEFORM_EXE="$<TARGET_FILE:deform>")
add_dependencies(test_cli_sculpt deform)
# The editor's side (issue 37): the Sculpt tool's session and script lines, local transitions in the
# document, its in-betweens and scene file.
dfm_test(test_sculpt_document SOURCES test_sculpt_document.cpp LIBS dfm_scene)
