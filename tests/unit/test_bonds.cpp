// The bond store: fixed capacity per particle, counted overflow, removal.
#include <gtest/gtest.h>

#include "dentsph/bonds.hpp"

namespace dentsph {
namespace {

TEST(BondStore, AddHasRemove) {
  BondStore b;
  b.resize(4, 3);
  EXPECT_TRUE(b.add(0, 1));
  EXPECT_TRUE(b.add(1, 0));
  EXPECT_TRUE(b.add(0, 2));
  EXPECT_TRUE(b.has(0, 1));
  EXPECT_TRUE(b.has(0, 2));
  EXPECT_FALSE(b.has(0, 3));
  EXPECT_FALSE(b.has(2, 0));
  EXPECT_EQ(b.count(0), 2);
  b.remove_at(0, 0);
  EXPECT_FALSE(b.has(0, 1));
  EXPECT_TRUE(b.has(0, 2));
  EXPECT_EQ(b.count(0), 1);
}

TEST(BondStore, OverflowIsRefusedAndCounted) {
  BondStore b;
  b.resize(5, 2);
  EXPECT_TRUE(b.add(0, 1));
  EXPECT_TRUE(b.add(0, 2));
  EXPECT_FALSE(b.add(0, 3));
  EXPECT_FALSE(b.add(0, 4));
  EXPECT_EQ(b.count(0), 2);
  EXPECT_FALSE(b.has(0, 3));
  EXPECT_EQ(b.counters.overflowed, 2u);
}

TEST(BondStore, GrowingKeepsExistingLists) {
  BondStore b;
  b.resize(2, 2);
  b.add(0, 1);
  b.add(1, 0);
  b.resize(3, 4);
  EXPECT_TRUE(b.has(0, 1));
  EXPECT_TRUE(b.has(1, 0));
  EXPECT_EQ(b.count(2), 0);
  EXPECT_TRUE(b.add(2, 0));
  EXPECT_EQ(b.capacity(), 4);
}

}  // namespace
}  // namespace dentsph
