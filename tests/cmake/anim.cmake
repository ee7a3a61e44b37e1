# core/anim: keyframes, interpolation, baking, animation manifolds; render/slice_pass (GL).
dfm_test(test_anim SOURCES test_anim.cpp LIBS dfm_anim)
dfm_test(test_manifold SOURCES test_manifold.cpp LIBS dfm_anim dfm_mesh)
dfm_test(test_gpu_slice SOURCES test_gpu_slice.cpp LIBS dfm_render dfm_anim GL)
dfm_test(test_transition SOURCES test_transition.cpp LIBS dfm_anim dfm_mesh TIMEOUT 900)
# As-rigid-as-possible interpolation of same-connectivity keys (Alexa 2002, 4.4; TetGen).
dfm_test(test_arap_interpolation SOURCES test_arap_interpolation.cpp LIBS dfm_anim)
# Transitions that travel, turn and meet by picked pairs (issue 30; key_alignment.h, space_warp.h).
dfm_test(test_transition_align SOURCES test_transition_align.cpp LIBS dfm_anim dfm_mesh TIMEOUT 900)
target_compile_definitions(test_transition_align PRIVATE DFM_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
# In-betweens against the documented morph: smoothness, fidelity, topology (issue 30; [heavy]: release).
dfm_test(test_transition_quality SOURCES test_transition_quality.cpp LIBS dfm_anim dfm_mesh TIMEOUT 900)
target_compile_definitions(test_transition_quality PRIVATE DFM_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
# The keys' signed distance (key_distance.h).
dfm_test(test_key_distance SOURCES test_key_distance.cpp LIBS dfm_anim)
# A lattice's values refitted to the field's own crossings (crossing_fit.h).
dfm_test(test_crossing_fit SOURCES test_crossing_fit.cpp LIBS dfm_anim)
# Short-lived topology between a transition's middle layers, merged (layer_transients.h).
dfm_test(test_layer_transients SOURCES test_layer_transients.cpp LIBS dfm_anim)
# Smoothing a transition's level set without changing its connectivity (level_set_relax.h).
dfm_test(test_transition_relax SOURCES test_transition_relax.cpp LIBS dfm_anim dfm_mesh)
# The 4D Delaunay triangulation of two layers from their 3D ones, against CGAL's dD (layer_pair_delaunay.h).
dfm_test(test_layer_pair_delaunay SOURCES test_layer_pair_delaunay.cpp LIBS dfm_anim)
# Refining a transition's middle lattice where the blend bulges off its chords (lattice_refinement.h).
dfm_test(test_lattice_refinement SOURCES test_lattice_refinement.cpp LIBS dfm_anim)
