# iblab_io: loading/validating environments, builtins, image writing.
iblab_add_cpu_test(environment_test ${CMAKE_CURRENT_SOURCE_DIR}/environment_test.cpp)
iblab_add_cpu_test(environment_resampling_test ${CMAKE_CURRENT_SOURCE_DIR}/environment_resampling_test.cpp)
# The content hash is checked against XXH3 of a byte stream the test builds by hand.
target_link_libraries(environment_resampling_test PRIVATE PkgConfig::XXHASH)
iblab_add_cpu_test(builtin_environments_test ${CMAKE_CURRENT_SOURCE_DIR}/builtin_environments_test.cpp)
iblab_add_cpu_test(image_writer_test ${CMAKE_CURRENT_SOURCE_DIR}/image_writer_test.cpp)
# The direct OpenEXR/Radiance codec against the OpenImageIO module, through the module
# alone: this executable must not link OpenImageIO (one test checks it is never loaded).
iblab_add_cpu_test(image_codec_direct_test ${CMAKE_CURRENT_SOURCE_DIR}/image_codec_direct_test.cpp)
target_compile_definitions(image_codec_direct_test PRIVATE IBLAB_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
foreach(test environment_test environment_resampling_test builtin_environments_test image_writer_test)
  # Tests read assets/ and the shared candidate assets at ${IBLAB_SOURCE_DIR}/../shared/assets
  # (skipped when absent), and check written files with OpenImageIO and nlohmann_json
  # directly, independently of the code under test.
  target_compile_definitions(${test} PRIVATE IBLAB_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  target_link_libraries(${test} PRIVATE OpenImageIO::OpenImageIO nlohmann_json::nlohmann_json)
endforeach()

# Reads the bundled courtyard.exr, so it lives with the suites that read files.
iblab_add_cpu_test(split_sum_bias_test ${CMAKE_CURRENT_SOURCE_DIR}/split_sum_bias_test.cpp)
target_link_libraries(split_sum_bias_test PRIVATE iblab_io)
target_compile_definitions(split_sum_bias_test PRIVATE IBLAB_SOURCE_DIR="${PROJECT_SOURCE_DIR}")

# The real-time specular approximations against the full integral (issue #14); reads
# builtin:white through iblab_io.
iblab_add_cpu_test(specular_approximations_test ${CMAKE_CURRENT_SOURCE_DIR}/specular_approximations_test.cpp)
target_link_libraries(specular_approximations_test PRIVATE iblab_io)
