brdfrig_add_bench(evaluate_study SOURCES evaluate_study.cc DEPS brdfrig::jobs brdfrig::evaluate)
