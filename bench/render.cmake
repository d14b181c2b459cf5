brdfrig_add_bench(render_frame SOURCES render_frame_bench.cc DEPS brdfrig::render)
