brdfrig_add_bench(evaluate_study SOURCES evaluate_study.cc DEPS brdfrig::jobs brdfrig::evaluate brdfrig::prior)
brdfrig_add_bench(model_ceiling SOURCES model_ceiling_bench.cc DEPS brdfrig::jobs brdfrig::reconstruct brdfrig::sim)
