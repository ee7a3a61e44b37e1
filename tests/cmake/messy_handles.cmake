# Issue 19: handles on (or within 1% of) messy surfaces bind through the robust volume.
dfm_test(test_messy_handles SOURCES test_messy_handles.cpp LIBS dfm_bind dfm_mesh dfm_rig)
