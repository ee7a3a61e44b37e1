# volume engineer: tetrahedralization (TetGen subprocess), handle geometry, winding numbers, robust volume.
dfm_test(test_winding_number SOURCES test_winding_number.cpp LIBS dfm_bind dfm_rig dfm_mesh)
dfm_test(test_tetrahedralize SOURCES test_tetrahedralize.cpp LIBS dfm_bind dfm_rig dfm_mesh)
dfm_test(test_bind_volume SOURCES test_bind_volume.cpp LIBS dfm_bind dfm_rig dfm_mesh TIMEOUT 600)
# Graph-cut segmentation of winding-number volumes (Jacobson 2013, 8.5.1) against the 0.5 threshold.
dfm_test(test_graph_cut SOURCES test_graph_cut.cpp LIBS dfm_bind dfm_rig dfm_mesh)
