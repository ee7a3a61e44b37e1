# Issue 19: pieces of a mesh without a handle move rigidly with the nearest handled piece.
dfm_test(test_bind_pieces SOURCES test_bind_pieces.cpp LIBS dfm_bind dfm_mesh dfm_rig)
