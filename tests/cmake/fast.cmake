# FAST posing (core/pose): ARAP elements, rotation clusters, the local-global solver.
dfm_test(test_fast SOURCES test_fast.cpp LIBS dfm_pose dfm_bind dfm_mesh dfm_rig)
