// nmesh/activity_index.h — the signal counters tau of the learning loop (eqs. (6)-(7) of the
// paper), with the cost per learning iteration O(1) amortised.
//
// The loop signals the winner (tau_w += 1, step 5), decays every counter (tau *= alpha, step 6),
// splits the most active vertex every Cvs iterations (step 7) and collapses the vertices that
// have not won for a while every Cec * n iterations (step 8). With up to 10^6 vertices none of
// the first three may touch all vertices, and step 8's query may do so only because it comes once
// every Cec * n iterations:
//
//   - decay is lazy: counters are stored multiplied by a global scale S = alpha^-(decays), so a
//     decay only multiplies S by 1/alpha and a signal adds S to one stored value. When S reaches
//     2^kScaleBits, S is divided by 2^kScaleBits (an "epoch" begins). Stored values are not
//     rescaled then: each remembers the epoch it was written in and is rescaled (by an exact power
//     of two) when next read. So renormalisation is O(1) for any alpha and any vertex count.
//   - most_active() looks at buckets of counters by magnitude, eight per octave (a bucket is the
//     exponent and 3 leading mantissa bits of the stored value, plus the epoch), kept as intrusive
//     lists, with a two-level bitmap of the non-empty ones: the top bucket is found with two
//     count-leading-zeros, then its few vertices are compared exactly. Bucket keys are invariant
//     under decay, so a decay moves nothing; a new epoch drops the lowest 2^12 buckets, whose
//     counters fell below the smallest normal double (2.2e-308): their vertices "retire" from
//     the buckets, in O(1), until a signal or set_counter brings them back.
//   - each vertex keeps the time of its last signal (or creation) and a stamp that orders the
//     signals and additions made at one time; the inactive vertices are found by a pass over the
//     records when step 8 asks for them (once every Cec * n iterations, so O(1) amortised per
//     iteration). Choice: a list in order of last signal would find them without that pass, but
//     moving the winner to its end touches the records of its two list neighbours, which are
//     arbitrary vertices: two cache misses per iteration on a large mesh, for a query made once
//     every Cec * n iterations.
//
// Accuracy: a counter read back after k decays since it was last written carries a relative
// rounding error of about k * 2^-52 (as does the plain loop `tau *= alpha`); counters below
// 2.2e-308 may be flushed to 0.
//
// Vertex ids are uint32 slots, typically mesh vertex indices: dense-ish and reused after removal.
#pragma once

#include <array>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "nmesh/prefetch.h"

namespace nmesh {

class ActivityIndex {
public:
    // Returned by most_active() when the index is empty.
    static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
    // Largest counter accepted by add() and set_counter(): a counter is stored multiplied by up
    // to 2^512 and must stay below the double range (2^1024) with room for signals.
    static constexpr double kMaxCounter = 1e150;
    // Smallest alpha accepted: one decay multiplies the scale by 1/alpha, which must not overflow
    // it (below 2^512 before, so 1/alpha < 2^511); a smaller factor is a reset, not a decay.
    static constexpr double kMinAlpha = 1e-100;

    // `alpha`: the decay factor of eq. (7), in [kMinAlpha, 1] (the paper uses values near 1).
    // Throws ParameterError otherwise.
    explicit ActivityIndex(double alpha);

    // Makes room for ids below `n`, so that adding them allocates nothing. O(n).
    void reserve(std::size_t n);

    // Adds vertex v with counter tau; its last-signal time is now(). O(1) amortised.
    // Preconditions: v != kNone, !contains(v). Throws ParameterError unless 0 <= tau <= kMaxCounter.
    void add(std::uint32_t v, double tau = 0.0);

    // Removes vertex v (the id may be added again later). O(1). Precondition: contains(v).
    void remove(std::uint32_t v);

    // Step 5: tau_v += 1 and the last-signal time of v becomes now(). O(1).
    // Precondition: contains(v).
    void signal(std::uint32_t v) {
        assert(contains(v));
        Node& n = nodes_[v];
        const std::uint64_t old_key = bucket_key(n);
        n.raw = current_raw(n) + scale_;
        n.epoch = epoch_;
        const std::uint64_t new_key = bucket_key(n);
        if (new_key != old_key) move_to_bucket(v, old_key, new_key);
        n.last_signal = now_;
        n.stamp = ++stamps_;
    }

    // Step 6: every counter is multiplied by alpha, and now() advances by one. O(1) amortised
    // (a new epoch, every 512 / log2(1/alpha) decays, costs a pass over 64 bitmap words).
    void decay() {
        ++now_;
        scale_ *= inv_alpha_;
        if (scale_ >= kScaleLimit) begin_epoch();
    }

    // The counter tau_v. O(1). Precondition: contains(v).
    double counter(std::uint32_t v) const {
        assert(contains(v));
        return current_raw(nodes_[v]) / scale_;
    }

    // Sets tau_v (its last-signal time is unchanged). O(1). Precondition: contains(v).
    // Throws ParameterError unless 0 <= tau <= kMaxCounter.
    void set_counter(std::uint32_t v, double tau);

    // The clock: the number of decay() calls so far.
    std::uint64_t now() const { return now_; }
    // The time of v's last signal, or of its add() if it has never been signalled.
    // Precondition: contains(v).
    std::uint64_t last_signal(std::uint32_t v) const {
        assert(contains(v));
        return nodes_[v].last_signal;
    }

    // The vertex with the largest counter, ties going to the smaller id; kNone when empty.
    // Cost: O(1) plus the vertices whose counters are within a factor 2^(1/8) of the largest (its
    // bucket) — a handful in the learning loop. When every counter is below 2.2e-308 (no signal
    // for a very long time) all vertices are compared: O(largest id).
    std::uint32_t most_active() const;

    // Appends to `out` every vertex whose last-signal time is < since, oldest first (equal times:
    // in the order they were signalled or added). O(largest id + k log k) for k vertices
    // appended.
    void collect_inactive(std::uint64_t since, std::vector<std::uint32_t>& out) const;

    std::size_t size() const { return size_; }
    // Starts loading v's record into the cache, ahead of a signal(v) (a hint; changes nothing).
    void prefetch(std::uint32_t v) const { prefetch_for_read(&nodes_[v]); }
    bool contains(std::uint32_t v) const { return v < nodes_.size() && nodes_[v].bucket_next != kNone; }
    double alpha() const { return alpha_; }

private:
    // The scale is renormalised by 2^kScaleBits: large, so that epochs are rare (every 512 decays
    // at alpha = 1/2), while counters times the scale stay in the double range (kMaxCounter).
    static constexpr int kScaleBits = 512;
    static constexpr double kScaleLimit = 0x1p512;
    // Bucket keys: the top 15 bits of the stored double (sign 0, 11 exponent bits, 3 mantissa
    // bits: eight buckets per octave), plus 8 * kScaleBits per epoch. Keys of live buckets span
    // kBuckets consecutive values; an epoch retires the lowest kEpochKeys of them.
    static constexpr int kMantissaShift = 49;
    static constexpr std::uint64_t kEpochKeys = 8 * kScaleBits;  // 4096 = 64 bitmap words
    static constexpr std::size_t kBuckets = 16384;               // 2^14: every finite double
    static constexpr std::size_t kWords = kBuckets / 64;
    static constexpr std::size_t kSummaryWords = kWords / 64;

    struct Node {
        double raw = 0.0;         // tau * scale, in the units of `epoch`
        std::uint64_t epoch = 0;  // the epoch raw was written in
        std::uint64_t last_signal = 0;
        std::uint64_t stamp = 0;  // orders the last signals (and additions): larger is later
        std::uint32_t bucket_prev = kNone, bucket_next = kNone;  // circular bucket list; kNone: absent
                                                                 // (stale, never followed, if retired)
    };

    // raw, rescaled to the current epoch: exact (a power-of-two scaling) unless it underflows.
    double current_raw(const Node& n) const {
        return n.epoch == epoch_ ? n.raw : rescale(n.raw, epoch_ - n.epoch);
    }
    // A value written `epochs` epochs ago, times 2^(-kScaleBits * epochs). Stored values are
    // below 2^1011, so after 4 epochs (2^-2048) nothing is left.
    static double rescale(double raw, std::uint64_t epochs) {
        constexpr double kDown = 0x1p-512;  // 2^-kScaleBits, exact
        if (epochs >= 4) return 0.0;
        for (; epochs > 0; --epochs) raw *= kDown;
        return raw;
    }
    static std::uint64_t bucket_key(const Node& n) {
        std::uint64_t bits;
        std::memcpy(&bits, &n.raw, sizeof bits);
        return (bits >> kMantissaShift) + n.epoch * kEpochKeys;
    }
    void move_to_bucket(std::uint32_t v, std::uint64_t old_key, std::uint64_t new_key);
    void link_bucket(std::uint32_t v, std::uint64_t key);
    void unlink_bucket(std::uint32_t v, std::uint64_t key);
    std::uint32_t best_in_list(std::uint32_t head) const;
    void begin_epoch();
    static double checked_counter(double tau, const char* what);

    double alpha_;
    double inv_alpha_;
    double scale_ = 1.0;  // alpha^-(decays) / 2^(kScaleBits * epoch_), in [1, kScaleLimit)
    std::uint64_t epoch_ = 0;
    std::uint64_t now_ = 0;
    std::size_t size_ = 0;

    std::vector<Node> nodes_;
    std::vector<std::uint32_t> bucket_heads_;  // kBuckets lists, indexed by key mod kBuckets
    // Bit i: the bucket of key epoch_ * kEpochKeys + i is non-empty; summary bit j: word j is not 0.
    std::array<std::uint64_t, kWords> bucket_bits_{};
    std::array<std::uint64_t, kSummaryWords> summary_bits_{};
    std::uint64_t stamps_ = 0;  // the last stamp given
};

}  // namespace nmesh
