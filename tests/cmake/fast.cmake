# FAST posing (core/pose): ARAP elements, rotation clusters, the local-global solver.
dfm_test(test_fast SOURCES test_fast.cpp LIBS dfm_pose dfm_bind dfm_mesh dfm_rig)
# Runs the `deform` executable end to end.
dfm_test(test_fast_cli SOURCES test_fast_cli.cpp LIBS dfm_mesh)
target_compile_definitions(test_fast_cli PRIVATE DFM_DEFORM_EXE="$<TARGET_FILE:deform>" DFM_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
add_dependencies(test_fast_cli deform)
# FAST with dynamics (Jacobson 2013, 7.7).
dfm_test(test_fast_dynamics SOURCES test_fast_dynamics.cpp LIBS dfm_pose dfm_bind dfm_mesh dfm_rig)
# Additional weight functions (Jacobson 2013, 7.3.3): the cigar of Fig. 7.7.
dfm_test(test_fast_additional_weights SOURCES test_fast_additional_weights.cpp LIBS dfm_pose dfm_bind dfm_mesh dfm_rig)
