# Weights (FEM, box QP, BBW, bind orchestration).
dfm_test(test_fem SOURCES test_fem.cpp LIBS dfm_bind)
dfm_test(test_bbw SOURCES test_bbw.cpp LIBS dfm_bind)
dfm_test(test_bind SOURCES test_bind.cpp LIBS dfm_bind dfm_mesh dfm_rig TIMEOUT 900)
dfm_test(test_coarse_level SOURCES test_coarse_level.cpp LIBS dfm_bind dfm_mesh)
dfm_test(test_monotone SOURCES test_monotone.cpp LIBS dfm_bind dfm_mesh dfm_rig TIMEOUT 600)
