dfm_test(test_gl_foundation SOURCES test_gl_foundation.cpp LIBS dfm_render GL)
