dfm_test(test_util SOURCES test_util.cpp LIBS dfm_util)
dfm_test(test_rig SOURCES test_rig.cpp LIBS dfm_rig)
