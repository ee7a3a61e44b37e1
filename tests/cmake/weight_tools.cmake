# Weight tools (limit, normalize with locks, smooth, mirror, report): the core functions.
dfm_test(test_weight_tools SOURCES test_weight_tools.cpp LIBS dfm_bind)
