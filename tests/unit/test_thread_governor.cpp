// The thread governor picks the thread count whose steps are fastest, from the step times it is
// given, and follows a change: a core taken by another process, then freed.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "dentsph/thread_governor.hpp"

namespace dentsph {
namespace {

// Runs `steps` steps whose wall time for t threads is cost(t); the share of them taken with
// `threads` threads among the last `tail` steps.
double share_with(ThreadGovernor& g, int steps, const std::function<double(int)>& cost, int threads, int tail) {
  int hits = 0;
  for (int k = 0; k < steps; ++k) {
    const int t = g.threads();
    if (k >= steps - tail && t == threads) ++hits;
    g.record(cost(t));
  }
  return double(hits) / tail;
}

const auto idle = [](int t) { return 1.0 / t; };           // two threads twice as fast
const auto one_core_busy = [](int t) { return t == 1 ? 1.0 : 2.5; };  // spinning barriers

TEST(ThreadGovernor, CandidatesArePowersOfTwoAndTheMaximum) {
  EXPECT_EQ(ThreadGovernor(1).candidates(), (std::vector<int>{1}));
  EXPECT_EQ(ThreadGovernor(2).candidates(), (std::vector<int>{1, 2}));
  EXPECT_EQ(ThreadGovernor(6).candidates(), (std::vector<int>{1, 2, 4, 6}));
  EXPECT_EQ(ThreadGovernor(0).threads(), 1);
  EXPECT_EQ(ThreadGovernor(4).threads(), 4) << "it starts with every thread";
}

TEST(ThreadGovernor, AnIdleMachineKeepsEveryThread) {
  ThreadGovernor g(2);
  EXPECT_GE(share_with(g, 5000, idle, 2, 4000), 0.9);
  EXPECT_NEAR(g.estimates()[0], 1.0, 1e-12);
  EXPECT_NEAR(g.estimates()[1], 0.5, 1e-12);
}

TEST(ThreadGovernor, ABusyCoreMakesItFallBackAndAFreedOneBringsItBack) {
  ThreadGovernor g(2);
  EXPECT_GE(share_with(g, 3000, idle, 2, 1000), 0.9);
  EXPECT_GE(share_with(g, 3000, one_core_busy, 1, 1000), 0.9);
  EXPECT_GE(share_with(g, 3000, idle, 2, 1000), 0.9);
}

TEST(ThreadGovernor, ExplorationCostsAtMostItsShare) {
  // One window in explore_every + 1 goes to another count: under a busy core the time lost to it
  // is bounded by that share of the slower count's extra cost.
  ThreadGovernorParams p;
  ThreadGovernor g(2, p);
  double total = 0;
  const int steps = 20000;
  for (int k = 0; k < steps; ++k) {
    const double c = one_core_busy(g.threads());
    total += c;
    g.record(c);
  }
  // Each try is one window with two threads (2.5 instead of 1) after explore_every windows with one.
  const double share = 1.0 / (p.explore_every + 1);
  EXPECT_LE(total, steps * (1 + 1.5 * share) + 2 * p.window * 2.5);
  EXPECT_GE(total, steps * (1 + 1.5 * share) * 0.9) << "the bound above is tight: tries are that often";
  EXPECT_GT(g.steps_with()[1], 0u) << "it kept trying two threads";
}

TEST(ThreadGovernor, BadTimesAreIgnored) {
  ThreadGovernor g(2);
  for (int k = 0; k < 1000; ++k) g.record(k % 3 == 0 ? std::nan("") : (k % 3 == 1 ? -1.0 : 1.0 / g.threads()));
  for (double e : g.estimates()) EXPECT_TRUE(std::isfinite(e) && e >= 0);
}

}  // namespace
}  // namespace dentsph
