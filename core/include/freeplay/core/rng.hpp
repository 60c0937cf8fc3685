#pragma once
// Deterministic random numbers: one root seed per episode, split into independent named streams.

#include <cstdint>
#include <string_view>
#include <utility>
#include <vector>

namespace freeplay {

/// SplitMix64 finaliser: a bijective 64-bit mix used to derive seeds.
std::uint64_t splitmix64(std::uint64_t x);

/// FNV-1a 64-bit hash of a byte string (stable across platforms and runs).
std::uint64_t fnv1a64(std::string_view bytes, std::uint64_t seed = 14695981039346656037ULL);

/// xoshiro256** generator with portable distributions (identical draws on every platform).
class Rng {
 public:
  using result_type = std::uint64_t;

  /// Seeds the four state words from `seed` through SplitMix64.
  explicit Rng(std::uint64_t seed = 0);

  static constexpr result_type min() { return 0; }
  static constexpr result_type max() { return ~result_type{0}; }
  /// Next raw 64-bit draw.
  result_type operator()();

  /// Uniform double in [0, 1) with 53 random bits.
  double uniform();
  /// Uniform double in [lo, hi).
  double uniform(double lo, double hi);
  /// Uniform integer in the closed range [lo, hi].
  std::int64_t uniform_int(std::int64_t lo, std::int64_t hi);
  /// Standard normal draw scaled to N(mean, sd²) (Box–Muller, no cached spare: draws stay aligned).
  double normal(double mean = 0.0, double sd = 1.0);
  /// Log-normal draw whose logarithm is N(mu, sigma²).
  double lognormal(double mu, double sigma);
  /// Exponential draw with the given rate (1 / mean).
  double exponential(double rate);
  /// True with probability p.
  bool bernoulli(double p);
  /// Index drawn with probability proportional to `weights` (non-negative, not all zero).
  std::size_t categorical(const std::vector<double>& weights);

  /// Fisher–Yates shuffle of a random-access range.
  template <typename Range>
  void shuffle(Range& range) {
    const auto n = static_cast<std::int64_t>(std::size(range));
    for (std::int64_t i = n - 1; i > 0; --i) {
      const auto j = uniform_int(0, i);
      using std::swap;
      swap(range[static_cast<std::size_t>(i)], range[static_cast<std::size_t>(j)]);
    }
  }

 private:
  std::uint64_t state_[4];
};

/// Draws of Rng::uniform_int(0, span − 1) for many calls with one span, its rejection limit worked out once: the
/// same draws from the same generator, one 64-bit division fewer each.
class IndexDraw {
 public:
  /// A draw over [0, span − 1]; span 0 stands for the full 64-bit range.
  explicit IndexDraw(std::uint64_t span)
      : span_(span), limit_(span == 0 ? Rng::max() : Rng::max() - (Rng::max() % span)) {}
  /// The next index from `rng`.
  std::uint64_t operator()(Rng& rng) const {
    if (span_ == 0) return rng();
    std::uint64_t x = rng();
    while (x >= limit_) x = rng();
    return x % span_;
  }

 private:
  std::uint64_t span_;
  std::uint64_t limit_;
};

/// One root seed split into independent, named per-component streams (order of requests does not matter).
class SeedSequence {
 public:
  /// Wraps the episode's root seed.
  explicit SeedSequence(std::uint64_t root_seed) : root_(root_seed) {}
  /// The root seed.
  std::uint64_t root() const { return root_; }
  /// Seed of the stream called `component` (e.g. "sandtray", "child.purple", "planner").
  std::uint64_t seed_for(std::string_view component) const;
  /// A generator on the stream called `component`.
  Rng stream(std::string_view component) const { return Rng(seed_for(component)); }
  /// A child sequence (e.g. per episode from a suite seed) whose streams are independent of this one's.
  SeedSequence derive(std::string_view name) const { return SeedSequence(seed_for(name)); }

 private:
  std::uint64_t root_;
};

}  // namespace freeplay
