brdfrig_add_bench(reconstruct SOURCES reconstruct_bench.cc DEPS brdfrig::reconstruct brdfrig::sim OpenCV::photo)
