#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <set>

#include "freeplay/core/rng.hpp"

using freeplay::Rng;
using freeplay::SeedSequence;

TEST(Rng, SameSeedSameSequence) {
  Rng a(42);
  Rng b(42);
  for (int i = 0; i < 1000; ++i) ASSERT_EQ(a(), b());
}

TEST(Rng, StreamsAreIndependentOfRequestOrder) {
  const SeedSequence seq(7);
  const auto first = seq.seed_for("child.purple");
  (void)seq.seed_for("sandtray");
  EXPECT_EQ(first, seq.seed_for("child.purple"));
  EXPECT_NE(seq.seed_for("child.purple"), seq.seed_for("child.yellow"));
  EXPECT_NE(SeedSequence(7).seed_for("x"), SeedSequence(8).seed_for("x"));
}

TEST(Rng, UniformMomentsWithinTolerance) {
  Rng rng(1);
  double sum = 0.0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const double u = rng.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
  }
  EXPECT_NEAR(sum / n, 0.5, 0.005);  // SE ≈ 0.00065
}

TEST(Rng, NormalMomentsWithinTolerance) {
  Rng rng(2);
  const int n = 200000;
  double sum = 0.0;
  double sum2 = 0.0;
  for (int i = 0; i < n; ++i) {
    const double z = rng.normal(3.0, 2.0);
    sum += z;
    sum2 += z * z;
  }
  const double mean = sum / n;
  EXPECT_NEAR(mean, 3.0, 0.03);
  EXPECT_NEAR(std::sqrt(sum2 / n - mean * mean), 2.0, 0.03);
}

TEST(Rng, UniformIntCoversClosedRange) {
  Rng rng(3);
  std::set<std::int64_t> seen;
  for (int i = 0; i < 1000; ++i) seen.insert(rng.uniform_int(-2, 2));
  EXPECT_EQ(seen, (std::set<std::int64_t>{-2, -1, 0, 1, 2}));
}

TEST(Rng, IndexDrawsAreTheRejectionDrawsOfUniformInt) {
  // The draw rule written out: reject raw draws at or above the largest multiple of the span, then reduce.
  const auto by_rule = [](Rng& rng, std::uint64_t span) -> std::uint64_t {
    if (span == 0) return rng();
    const std::uint64_t limit = Rng::max() - (Rng::max() % span);
    std::uint64_t x = rng();
    while (x >= limit) x = rng();
    return x % span;
  };
  for (const std::uint64_t span : {std::uint64_t{0}, std::uint64_t{1}, std::uint64_t{2}, std::uint64_t{7},
                                   std::uint64_t{1} << 32, (std::uint64_t{1} << 63) + 1, Rng::max()}) {
    Rng a(11);
    Rng b(11);
    Rng c(11);
    const freeplay::IndexDraw draw(span);
    for (int i = 0; i < 2000; ++i) {
      const std::uint64_t expected = by_rule(a, span);
      EXPECT_EQ(draw(b), expected) << span;
      if (span != 0 && span <= static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())) {
        EXPECT_EQ(static_cast<std::uint64_t>(c.uniform_int(0, static_cast<std::int64_t>(span - 1))), expected) << span;
      }
    }
  }
}

TEST(Rng, CategoricalFollowsWeights) {
  Rng rng(4);
  int counts[3] = {0, 0, 0};
  for (int i = 0; i < 30000; ++i) ++counts[rng.categorical({1.0, 0.0, 3.0})];
  EXPECT_EQ(counts[1], 0);
  EXPECT_NEAR(counts[2] / 30000.0, 0.75, 0.02);
  EXPECT_THROW(rng.categorical({0.0, 0.0}), std::invalid_argument);
}
