brdfrig_add_bench(brdf_eval SOURCES brdf_eval_bench.cc DEPS brdfrig::brdf benchmark::benchmark)
