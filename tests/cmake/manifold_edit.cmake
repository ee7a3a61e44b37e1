# Space-time Laplacian editing of animation manifolds (issue 35; Southern 2008 ch. 4).
dfm_test(test_manifold_edit SOURCES test_manifold_edit.cpp LIBS dfm_anim dfm_mesh)
