# iblab_scene: meshes, procedural spheres, glTF loading (real models, the generated test
# model and a corpus of broken files made on the fly) and export.
iblab_add_cpu_test(scene_mesh_test ${CMAKE_CURRENT_SOURCE_DIR}/scene_mesh_test.cpp)
iblab_add_cpu_test(scene_sphere_test ${CMAKE_CURRENT_SOURCE_DIR}/scene_sphere_test.cpp)
iblab_add_cpu_test(scene_gltf_test ${CMAKE_CURRENT_SOURCE_DIR}/scene_gltf_test.cpp)
iblab_add_cpu_test(scene_gltf_robustness_test ${CMAKE_CURRENT_SOURCE_DIR}/scene_gltf_robustness_test.cpp)
iblab_add_cpu_test(scene_gltf_features_test ${CMAKE_CURRENT_SOURCE_DIR}/scene_gltf_features_test.cpp)
foreach(test scene_mesh_test scene_sphere_test scene_gltf_test scene_gltf_robustness_test scene_gltf_features_test)
  target_link_libraries(${test} PRIVATE iblab_scene)
endforeach()
foreach(test scene_gltf_test scene_gltf_robustness_test scene_gltf_features_test)
  # The glTF tests read assets/models and the shared candidate models (skipped when
  # absent), and build or inspect glTF JSON and PNGs independently of the code under test.
  target_compile_definitions(${test} PRIVATE IBLAB_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
                                             IBLAB_SHARED_ASSETS="${PROJECT_SOURCE_DIR}/../shared/assets")
  target_link_libraries(${test} PRIVATE nlohmann_json::nlohmann_json OpenImageIO::OpenImageIO)
endforeach()
target_link_libraries(scene_gltf_features_test PRIVATE ZLIB::ZLIB) # malformed_images.hpp writes PNG CRCs

# The one-triangle model, its .gltf/.glb writers and the load-error checks that the
# robustness and features tests share (gltf_test_files.hpp).
add_library(gltf_test_files STATIC ${CMAKE_CURRENT_SOURCE_DIR}/gltf_test_files.cpp)
target_include_directories(gltf_test_files PUBLIC ${PROJECT_SOURCE_DIR}/tests/support)
target_link_libraries(gltf_test_files PUBLIC iblab_scene GTest::gtest nlohmann_json::nlohmann_json
                                      PRIVATE OpenImageIO::OpenImageIO iblab_warnings)
foreach(test scene_gltf_robustness_test scene_gltf_features_test)
  target_link_libraries(${test} PRIVATE gltf_test_files)
endforeach()
