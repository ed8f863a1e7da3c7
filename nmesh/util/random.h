// nmesh/random.h — a small, fast, seeded random generator (xoshiro256**, Blackman and Vigna).
//
// The same seed gives the same sequence on every platform (unlike the std distributions), which
// is what makes reconstructions bit-for-bit reproducible.
#pragma once

#include <cstdint>

namespace nmesh {

class Random {
public:
    explicit Random(std::uint64_t seed) {
        // Expand the seed with splitmix64 so that nearby seeds give unrelated streams.
        for (std::uint64_t& s : s_) {
            seed += 0x9e3779b97f4a7c15ull;
            std::uint64_t z = seed;
            z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
            z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
            s = z ^ (z >> 31);
        }
    }

    std::uint64_t next() {
        const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
        const std::uint64_t t = s_[1] << 17;
        s_[2] ^= s_[0];
        s_[3] ^= s_[1];
        s_[1] ^= s_[2];
        s_[0] ^= s_[3];
        s_[2] ^= t;
        s_[3] = rotl(s_[3], 45);
        return result;
    }

    // Uniform in [0, n) for n < 2^32 (Lemire's multiply-shift; the bias is below 2^-32 * n).
    std::uint32_t below(std::uint32_t n) { return std::uint32_t(((next() >> 32) * std::uint64_t(n)) >> 32); }

    // Uniform in [0, 1).
    double uniform() { return double(next() >> 11) * 0x1.0p-53; }

private:
    static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
    std::uint64_t s_[4];
};

}  // namespace nmesh
