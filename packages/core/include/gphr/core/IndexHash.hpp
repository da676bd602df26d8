#pragma once
/// @file
/// A hash of a global index, the same on any rank count: what makes the CountSketch of the
/// empirical quadrature's rows (EmpiricalQuadrature.cpp) and the stored basis' fingerprint
/// (ReducedModelFile.cpp) independent of the distribution.

namespace gphr {

/// splitmix64 (Steele, Lea & Flood 2014) at position `index` + 1 of the stream seeded by `seed`:
/// 64 well-mixed bits per (seed, index). Written out rather than taken from the standard library: its
/// engines are sequential (the i-th value costs i steps), this is O(1) per index.
inline unsigned long long hashIndex(unsigned long long seed, unsigned long long index) {
  unsigned long long x = seed + 0x9E3779B97F4A7C15ull * (index + 1);
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

}  // namespace gphr
