# Other tools' bakes: the KTX readers (iblab_io) and the import of cmgen / glTF-IBL-Sampler
# bakes. imported_bake_test runs Debian's cmgen (libfilament-tools) when installed.
iblab_add_cpu_test(ktx_reader_test ${CMAKE_CURRENT_SOURCE_DIR}/ktx_reader_test.cpp)
iblab_add_cpu_test(imported_bake_test ${CMAKE_CURRENT_SOURCE_DIR}/imported_bake_test.cpp)
# Export then import (the engine export's writers, the import's readers): links the bake
# layer for the export's reorientation (CPU code, no context).
iblab_add_cpu_test(ktx_roundtrip_test ${CMAKE_CURRENT_SOURCE_DIR}/ktx_roundtrip_test.cpp)
target_link_libraries(ktx_roundtrip_test PRIVATE iblab_bake)
