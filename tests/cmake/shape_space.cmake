# Shape spaces from morphing (Alexa 2002, ch. 5): synthesis by Eq. 5.31's chain, linear analysis, the pad.
dfm_test(test_shape_space SOURCES test_shape_space.cpp LIBS dfm_anim dfm_mesh)
