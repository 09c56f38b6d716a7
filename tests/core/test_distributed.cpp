// core/distributed.h without a launcher: one process (rank 0 of 1), the partitions for any rank count, the byte
// serialisation, and the distributed ordered reduce falling back to ordered_reduce. The runs over several ranks
// are tests/mpi.
#include <catch2/catch.hpp>
#include <numeric>
#include <vector>

#include "core/distributed.h"

using namespace radwalk;
using namespace radwalk::distributed;

TEST_CASE("without a launcher a run is one process", "[distributed]") {
  CHECK(rank() == 0);
  CHECK(size() == 1);
  CHECK(is_root());
  const Range all = my_block(17);
  CHECK(all.begin == 0);
  CHECK(all.end == 17);
  CHECK(max_over_ranks(2.5) == 2.5);
  CHECK(bytes_received() == 0);
}

TEST_CASE("block partitions cover 0 to n in order with sizes differing by at most one", "[distributed]") {
  for (std::size_t n : {0u, 1u, 2u, 7u, 100u, 1001u})
    for (int ranks = 1; ranks <= 7; ++ranks) {
      INFO("n " << n << ", ranks " << ranks);
      const std::vector<Range> blocks = all_blocks(n, ranks);
      REQUIRE(blocks.size() == static_cast<std::size_t>(ranks));
      std::size_t at = 0, smallest = n, largest = 0;
      for (const Range& b : blocks) {
        CHECK(b.begin == at);
        at = b.end;
        smallest = std::min(smallest, b.size());
        largest = std::max(largest, b.size());
      }
      CHECK(at == n);
      CHECK(largest - smallest <= 1);
    }
}

TEST_CASE("weighted blocks are contiguous and within the largest weight of an equal share", "[distributed]") {
  std::vector<double> weights;
  for (int i = 0; i < 500; ++i) weights.push_back(1 + (i * 37 % 11) + (i == 250 ? 40 : 0));  // uneven, one heavy
  const double total = std::accumulate(weights.begin(), weights.end(), 0.0);
  const double heaviest = *std::max_element(weights.begin(), weights.end());
  for (int ranks = 1; ranks <= 6; ++ranks) {
    const std::vector<Range> blocks = weighted_blocks(weights, ranks);
    REQUIRE(blocks.size() == static_cast<std::size_t>(ranks));
    std::size_t at = 0;
    for (const Range& b : blocks) {
      INFO("ranks " << ranks << ", block [" << b.begin << ", " << b.end << ")");
      CHECK(b.begin == at);
      at = b.end;
      const double w = std::accumulate(weights.begin() + long(b.begin), weights.begin() + long(b.end), 0.0);
      CHECK(std::abs(w - total / ranks) <= heaviest);
    }
    CHECK(at == weights.size());
  }
  // No weight at all: equal blocks.
  const std::vector<Range> zero = weighted_blocks(std::vector<double>(10, 0.0), 3);
  CHECK(zero[0].size() == 4);
  CHECK(zero[2].end == 10);
  // A planted error shows the check can fail: one weight above the rest by more than a share is not balanced.
  std::vector<double> lopsided(10, 1.0);
  lopsided[0] = 100;
  const std::vector<Range> two = weighted_blocks(lopsided, 2);
  const double first = std::accumulate(lopsided.begin(), lopsided.begin() + long(two[0].end), 0.0);
  CHECK(std::abs(first - 109.0 / 2) > 1.0);  // beyond a weight of 1, within the heaviest (100)
  CHECK(std::abs(first - 109.0 / 2) <= 100.0);
}

TEST_CASE("bytes written are read back in order", "[distributed]") {
  std::vector<char> bytes;
  ByteWriter out(bytes);
  out.put(std::uint64_t{42});
  const double values[3] = {1.5, -0.0, 3e300};
  out.put_bytes(values, sizeof values);
  out.put(7);
  ByteReader in(bytes);
  CHECK(in.get<std::uint64_t>() == 42);
  double back[3];
  in.get_bytes(back, sizeof back);
  CHECK(std::memcmp(back, values, sizeof values) == 0);
  CHECK(in.get<int>() == 7);
  CHECK(in.done());
  CHECK_THROWS(in.get<int>());  // reading past the end is an internal error, not a silent read
}

TEST_CASE("the distributed ordered reduce of one process is ordered_reduce", "[distributed]") {
  // Combining in chunk order: a floating-point sum whose result depends on the order.
  auto map = [](std::size_t c) { return c % 2 ? 1e16 : 1.0 / double(c + 1); };
  double ordered = 0, distributed_sum = 0;
  ordered_reduce(100, 4, map, [&](double p) { ordered += p; });
  distributed_ordered_reduce(
      100, 4, map, [&](double p) { distributed_sum += p; },
      [](double p, ByteWriter& w) { w.put(p); }, [](ByteReader& r) { return r.get<double>(); });
  CHECK(distributed_sum == ordered);
  std::vector<double> items = {1, 2, 3};
  share_blocks(items, all_blocks(items.size()));
  CHECK(items == std::vector<double>{1, 2, 3});
  CHECK(allgather_concat(items) == items);
}
