// Seeded, platform-independent random numbers: one independent stream per work item, so
// results do not depend on thread count or scheduling.
#pragma once

#include <cstdint>

namespace shanshui {

//! SplitMix64 finaliser (Steele, Lea, Flood 2014): a bijective 64-bit mix.
constexpr std::uint64_t splitMix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

//! The random value of item `index` of the stream named by `seed`.
constexpr std::uint64_t streamValue(std::uint64_t seed, std::uint64_t index) {
  return splitMix64(splitMix64(seed) ^ index);
}

}  // namespace shanshui
