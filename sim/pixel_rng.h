// Counter-based random numbers for noise: every (seed, frame, effect, pixel) has its own
// stream, so an image is the same whatever the thread count or the order pixels are visited,
// and adding one noise effect does not change another's realization.
#pragma once

#include <cmath>
#include <cstdint>

namespace brdfrig::sim {

// SplitMix64 finalizer (Steele, Lea, Flood 2014): a bijective 64-bit mix.
inline std::uint64_t Mix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

class PixelRng {
 public:
  PixelRng(std::uint64_t seed, std::uint64_t frame, std::uint64_t effect, std::uint64_t pixel)
      : state_(Mix64(Mix64(Mix64(Mix64(seed) ^ frame) ^ effect) ^ pixel)) {}

  // Uniform in (0, 1].
  double Uniform() {
    state_ += 0x9E3779B97F4A7C15ull;
    return (static_cast<double>(Mix64(state_) >> 11) + 1.0) * 0x1.0p-53;
  }

  // Standard normal (Box–Muller; one value per call keeps the stream layout simple).
  double Gaussian() {
    const double u1 = Uniform();
    const double u2 = Uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
  }

  // Poisson count with mean `lambda` >= 0: exact (multiplication method) for small means, the
  // rounded normal approximation for large ones (its error is far below one count's width).
  double Poisson(double lambda) {
    if (lambda <= 0) return 0;
    if (lambda < 64) {
      const double limit = std::exp(-lambda);
      double product = Uniform();
      int k = 0;
      while (product > limit) {
        product *= Uniform();
        ++k;
      }
      return k;
    }
    return std::fmax(0.0, std::round(lambda + std::sqrt(lambda) * Gaussian()));
  }

 private:
  std::uint64_t state_;
};

}  // namespace brdfrig::sim
