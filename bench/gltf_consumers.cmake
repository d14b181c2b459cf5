# What three.js and Blender draw of fitted materials' glTF versions (docs/gltf.md). Built where
# the consumers' scene library is (release: tests/consumers).
if(TARGET brdfrig_consumer_scene)
  brdfrig_add_bench(gltf_consumers SOURCES gltf_consumers.cc
                    DEPS brdfrig_consumer_scene brdfrig::brdf)
  target_include_directories(bench_gltf_consumers PRIVATE ${PROJECT_SOURCE_DIR})
  target_compile_definitions(bench_gltf_consumers PRIVATE BRDFRIG_BINARY="$<TARGET_FILE:brdfrig>")
  add_dependencies(bench_gltf_consumers brdfrig)
endif()
