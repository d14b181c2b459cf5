brdfrig_add_bench(reconstruct SOURCES reconstruct_bench.cc DEPS brdfrig::reconstruct brdfrig::sim OpenCV::photo)
brdfrig_add_bench(marker_pose SOURCES marker_pose_bench.cc DEPS brdfrig::jobs brdfrig::reconstruct brdfrig::sim)
