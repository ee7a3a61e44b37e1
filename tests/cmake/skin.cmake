# Pose (rig: FK, pseudo-edges, pose files) and skinning (LBS, DQS, STBS) tests.
dfm_test(test_pose SOURCES test_pose.cpp LIBS dfm_rig dfm_mesh)
dfm_test(test_skin SOURCES test_skin.cpp LIBS dfm_skin)
dfm_test(test_skin_arm SOURCES test_skin_arm.cpp LIBS dfm_skin dfm_mesh)
dfm_test(test_gpu_skin SOURCES test_gpu_skin.cpp LIBS dfm_render dfm_skin dfm_mesh GL)
