# Animations from base shapes (Alexa 2003, 7.2-7.3): the PCA decomposition after rigid alignment, the
# .pca file, its glTF morph-target export (Khronos validator under Node.js) and `deform compress/decompress`.
# The independent references (Horn alignment, Jacobi SVD) of tests/pca_test_frames.h, compiled once.
add_library(dfm_test_pca STATIC pca_test_frames.cpp)
target_link_libraries(dfm_test_pca PUBLIC dfm_mesh)
dfm_test(test_pca_animation SOURCES test_pca_animation.cpp LIBS dfm_anim dfm_test_pca)
dfm_test(test_pca_file SOURCES test_pca_file.cpp LIBS dfm_anim dfm_test_pca)
dfm_test(test_pca_gltf SOURCES test_pca_gltf.cpp LIBS dfm_export dfm_test_pca nlohmann_json::nlohmann_json TIMEOUT 600)
target_compile_definitions(test_pca_gltf PRIVATE DFM_GLTF_VALIDATOR_DIR="${CMAKE_CURRENT_SOURCE_DIR}/gltf")
dfm_test(test_pca_cli SOURCES test_pca_cli.cpp LIBS dfm_scene dfm_test_pca)
target_compile_definitions(test_pca_cli PRIVATE DEFORM_EXE="$<TARGET_FILE:deform>")
add_dependencies(test_pca_cli deform)
