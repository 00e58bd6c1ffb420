# iblab_ibl suites: the IBL math, no GL context and no image files needed.
iblab_add_cpu_test(conventions_test ${CMAKE_CURRENT_SOURCE_DIR}/conventions_test.cpp)
iblab_add_cpu_test(sampling_test ${CMAKE_CURRENT_SOURCE_DIR}/sampling_test.cpp)
iblab_add_cpu_test(brdf_test ${CMAKE_CURRENT_SOURCE_DIR}/brdf_test.cpp)
iblab_add_cpu_test(sh_test ${CMAKE_CURRENT_SOURCE_DIR}/sh_test.cpp)
iblab_add_cpu_test(reference_test ${CMAKE_CURRENT_SOURCE_DIR}/reference_test.cpp)
iblab_add_cpu_test(brdf_lut_test ${CMAKE_CURRENT_SOURCE_DIR}/brdf_lut_test.cpp)
iblab_add_cpu_test(tonemap_test ${CMAKE_CURRENT_SOURCE_DIR}/tonemap_test.cpp)
iblab_add_cpu_test(error_metrics_test ${CMAKE_CURRENT_SOURCE_DIR}/error_metrics_test.cpp)
# The committed fitted-lobe table: no steps between neighbouring cells (the rings of rough spheres).
iblab_add_cpu_test(lobe_table_smoothness_test ${CMAKE_CURRENT_SOURCE_DIR}/lobe_table_smoothness_test.cpp)
# The fitted lobe's shading lights: which groups, their flux, the residual chain, bake.json's form.
iblab_add_cpu_test(shading_lights_test ${CMAKE_CURRENT_SOURCE_DIR}/shading_lights_test.cpp)
# The fitted lobe's read floor (accuracy_study's read_floor.cpp, compiled in).
iblab_add_cpu_test(lobe_read_floor_test ${CMAKE_CURRENT_SOURCE_DIR}/lobe_read_floor_test.cpp
                   ${PROJECT_SOURCE_DIR}/renderer/lab/accuracy_study/read_floor.cpp)
target_include_directories(lobe_read_floor_test PRIVATE ${PROJECT_SOURCE_DIR}/renderer/lab/accuracy_study)
