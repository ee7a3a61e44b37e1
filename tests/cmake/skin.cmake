# Pose (rig: FK, pseudo-edges, pose files) and skinning (LBS, DQS, STBS) tests.
dfm_test(test_pose SOURCES test_pose.cpp LIBS dfm_rig dfm_mesh)
dfm_test(test_skin SOURCES test_skin.cpp LIBS dfm_skin)
dfm_test(test_skin_arm SOURCES test_skin_arm.cpp LIBS dfm_skin dfm_mesh)
dfm_test(test_gpu_skin SOURCES test_gpu_skin.cpp LIBS dfm_render dfm_skin dfm_mesh GL)
# Runs the `deform` executable end to end.
# The endpoint weights' filter curve (Fig. 6.9).
dfm_test(test_endpoint_filter SOURCES test_endpoint_filter.cpp LIBS dfm_skin)
dfm_test(test_pose_cli SOURCES test_pose_cli.cpp LIBS dfm_skin dfm_mesh)
target_compile_definitions(test_pose_cli PRIVATE DFM_DEFORM_EXE="$<TARGET_FILE:deform>")
add_dependencies(test_pose_cli deform)
# The candy wrapper (Jacobson 2013, Fig. 6.1) on arm.obj: LBS collapses a turned wrist, STBS keeps it.
dfm_test(test_candy_wrapper SOURCES test_candy_wrapper.cpp LIBS dfm_scene)
# STBS endpoint weights from the bind (Jacobson 2013, 6.2.3): Eq. 6.7, the joint constraints, the arm and hand.
dfm_test(test_endpoint_weights SOURCES test_endpoint_weights.cpp LIBS dfm_bind dfm_skin dfm_mesh)
# Weight transfer onto other surfaces (issue 34; Abdrashitov et al. 2023): closest points, then inpainting.
dfm_test(test_weight_transfer SOURCES test_weight_transfer.cpp LIBS dfm_bind dfm_mesh)
