# Playback from cached slice topologies (issue 16): core/anim/interval_slice (CPU), the GPU pass
# render/interval_slice_pass (GL), and the editor's choice of cache or general pass (no GL).
dfm_test(test_interval_slice SOURCES test_interval_slice.cpp LIBS dfm_anim dfm_mesh)
dfm_test(test_gpu_interval_slice GL SOURCES test_gpu_interval_slice.cpp ${PROJECT_SOURCE_DIR}/app/editor/slice_cache.cpp
         LIBS dfm_render dfm_anim)
dfm_test(test_slice_cache SOURCES test_slice_cache.cpp ${PROJECT_SOURCE_DIR}/app/editor/slice_cache.cpp
         ${PROJECT_SOURCE_DIR}/app/editor/interval_prefetch.cpp ${PROJECT_SOURCE_DIR}/render/interval_records.cpp
         LIBS dfm_anim dfm_mesh)
