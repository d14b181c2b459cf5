brdfrig_add_bench(evaluate_study SOURCES evaluate_study.cc DEPS brdfrig::jobs brdfrig::evaluate brdfrig::prior)
brdfrig_add_bench(model_ceiling SOURCES model_ceiling_bench.cc DEPS brdfrig::jobs brdfrig::reconstruct brdfrig::sim)
# Which source the glTF version is fitted to (docs/gltf.md).
brdfrig_add_bench(gltf_source_study SOURCES gltf_source_study.cc DEPS brdfrig::jobs)
target_include_directories(bench_gltf_source_study PRIVATE ${PROJECT_SOURCE_DIR})
# What each calibration of a departed rig buys on the measured materials (docs/calibration_value.md).
brdfrig_add_bench(calibration_value SOURCES calibration_value_bench.cc
                  DEPS brdfrig::jobs brdfrig::calibrate brdfrig::sim OpenCV::imgproc OpenCV::imgcodecs)
