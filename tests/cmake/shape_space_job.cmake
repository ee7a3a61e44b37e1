# The Shape space panel's ARAP worker (app/editor/shape_space_job): supersede, cancel, and the result
# against core's synchronous synthesis (Alexa 2002, ch. 5). No GL: built from its source with core.
dfm_test(test_shape_space_job SOURCES test_shape_space_job.cpp ${PROJECT_SOURCE_DIR}/app/editor/shape_space_job.cpp
         ${PROJECT_SOURCE_DIR}/app/editor/shape_space_cursor.cpp
         LIBS dfm_anim dfm_mesh TIMEOUT 120)
