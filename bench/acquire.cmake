brdfrig_add_bench(acquire_session SOURCES acquire_session_bench.cc
                  DEPS brdfrig::acquire brdfrig::sim)
