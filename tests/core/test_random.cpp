#include <gtest/gtest.h>

#include <cstdint>
#include <set>

#include "fogradar/core/random.hpp"

namespace fogradar {
namespace {

// The radar's streams are the ones every earlier version drew from: RandomStream(seed, step, index)
// as specified by its constructor. Earlier result files stay reproducible only if this holds.
TEST(SensorStream, RadarStreamsAreTheOriginalStepIndexStreams) {
  for (std::uint64_t seed : {0ULL, 1ULL, 0xFFFF'FFFF'FFFF'FFFFULL}) {
    for (std::uint64_t step : {0ULL, 4ULL}) {
      for (std::uint64_t index : {0ULL, 199ULL}) {
        RandomStream expected(seed, step, index);
        RandomStream actual = sensor_stream(seed, 0, step, index);
        for (int i = 0; i < 8; ++i) EXPECT_EQ(actual(), expected());
      }
    }
  }
}

// Streams of different sensors at the same (seed, step, index), and of one sensor at neighbouring
// keys, must not coincide: 64-bit first words of independent streams collide with probability
// ~n^2 / 2^65, about 1e-13 for these 4 x 2 x 5 x 200 keys, so any repeat is a derivation defect.
// Sensor keys 0, 1, 2 are the radar's, the lidar's and the camera's; 3 a further sensor's.
TEST(SensorStream, SensorsDrawDistinctStreams) {
  std::set<std::uint64_t> first_words;
  std::size_t keys = 0;
  for (std::uint64_t sensor : {0ULL, 1ULL, 2ULL, 3ULL}) {
    for (std::uint64_t seed : {1ULL, 2ULL}) {
      for (std::uint64_t step = 0; step < 5; ++step) {
        for (std::uint64_t index = 0; index < 200; ++index) {
          RandomStream stream = sensor_stream(seed, sensor, step, index);
          first_words.insert(stream());
          ++keys;
        }
      }
    }
  }
  EXPECT_EQ(first_words.size(), keys);
}

}  // namespace
}  // namespace fogradar
