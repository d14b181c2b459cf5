brdfrig_add_bench(prior_study SOURCES prior_study.cc
                  DEPS brdfrig::reconstruct brdfrig::coverage brdfrig::evaluate brdfrig::prior
                       brdfrig::jobs)
