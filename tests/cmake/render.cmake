dfm_test(test_gl_foundation SOURCES test_gl_foundation.cpp LIBS dfm_render GL)
dfm_test(test_surface_pass SOURCES test_surface_pass.cpp LIBS dfm_render GL)
