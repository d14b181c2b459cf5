# Simulator throughput: megapixels/s of the ideal default scene, the cost of each effect, and
# every effect listed-but-disabled against the ideal scene.
brdfrig_add_bench(sim SOURCES sim_bench.cc DEPS brdfrig::sim)
