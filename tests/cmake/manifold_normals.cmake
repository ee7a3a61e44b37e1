# core/anim/manifold_normals: smooth 4D vertex normals and the CPU slices' normals.
dfm_test(test_manifold_normals SOURCES test_manifold_normals.cpp LIBS dfm_anim dfm_mesh)
