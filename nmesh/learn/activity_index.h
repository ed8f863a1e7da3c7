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
//   - each vertex keeps a stamp, from a counter of all signals and additions, that orders them:
//     the stamp of its last signal (or of its addition). mark() is the latest stamp given, so the
//     vertices not signalled since a mark are those whose stamps are <= it; they are found by a
//     pass over the records when step 8 asks for them (once every Cec * n iterations, so O(1)
//     amortised per iteration). Choice: a list in order of last signal would find them without
//     that pass, but moving the winner to its end touches the records of its two list
//     neighbours, which are arbitrary vertices: two cache misses per iteration on a large mesh,
//     for a query made once every Cec * n iterations. No record holds a time: clock_mark(), the
//     mark as of the latest decay, serves callers that count periods in decays, as step 8 does
//     (a vertex added after an iteration's decay belongs to the next period).
//   - a record is 24 bytes per vertex: the stored counter, the two bucket links, and one word
//     with the stamp in its high 48 bits and the epoch of the stored counter modulo 2^16 in its
//     low 16. The full epoch is epoch_ minus the lag (epoch_ - stored) mod 2^16, which is right
//     while no record lags 2^16 epochs or more. A record that lags 4 epochs or more reads as 0
//     (rescale) and is retired, so every 2^15 epochs a pass rewrites the epoch of those so that
//     they lag exactly 4: the same counter, still retired, and no lag reaches 2^15 + 4 before the
//     next pass. That pass is O(largest id) once every 2^15 epochs, and an epoch comes at most
//     once per decay (about every 1.5 decays at the smallest alpha, every 6,900 at alpha = 0.95):
//     at most largest id / 2^15 records per decay (31 for 10^6 vertices), so O(1) amortised per
//     decay for any mesh that fits in memory. Stamps have 48 bits: an index gives at most
//     2^48 - 1 (2.8e14) of them, about nine years at a million signals a second; beyond,
//     signal() and add() throw InputError (a run too long for the index) and change nothing.
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

#include "nmesh/util/prefetch.h"

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
    // Gives back the room for ids from `n` on, none of which may be in the index (for a compact
    // copy; reserve() makes it again). O(n).
    void shrink_ids(std::size_t n);

    // Adds vertex v with counter tau; its last stamp is a new one (later than mark()).
    // O(1) amortised. Preconditions: v != kNone, !contains(v). Throws ParameterError unless
    // 0 <= tau <= kMaxCounter, or when the stamps are exhausted (see the header comment).
    void add(std::uint32_t v, double tau = 0.0);

    // Removes vertex v (the id may be added again later). O(1). Precondition: contains(v).
    void remove(std::uint32_t v);

    // Step 5: tau_v += 1 and v's last stamp becomes a new one (later than mark()). O(1).
    // Precondition: contains(v). Throws ParameterError, changing nothing, when the stamps are
    // exhausted (2^48 - 1 signals and additions: a branch never taken in practice).
    void signal(std::uint32_t v) { signal(v, 1.0); }
    // The same with tau_v += weight (weight > 0, at most a few thousand): a signal that counts
    // for more than one win (Parameters::adaptivity).
    void signal(std::uint32_t v, double weight) {
        assert(contains(v));
        const std::uint64_t stamps = next_stamps();
        Node& n = nodes_[v];
        const std::uint64_t old_key = bucket_key(n);
        const double raw = current_raw(n) + scale_ * weight;
        n.raw = raw;
        n.stamp_epoch = stamps | (epoch_ & kEpochMask);
        stamps_ = stamps;
        const std::uint64_t new_key = key(raw, 0);
        if (new_key != old_key) move_to_bucket(v, old_key, new_key);
    }

    // Step 6: every counter is multiplied by alpha, and now() advances by one; clock_mark()
    // becomes mark(). O(1) amortised (a new epoch, every 512 / log2(1/alpha) decays, costs a
    // pass over 64 bitmap words, and one in 2^15 a pass over the records: see the header comment).
    void decay() {
        clock_mark_ = stamps_;
        ++now_;
        scale_ *= inv_alpha_;
        if (scale_ >= kScaleLimit) begin_epoch();
    }

    // The counter tau_v. O(1). Precondition: contains(v).
    double counter(std::uint32_t v) const {
        assert(contains(v));
        return current_raw(nodes_[v]) / scale_;
    }

    // Sets tau_v (its last stamp is unchanged: this is not a signal). O(1).
    // Precondition: contains(v). Throws ParameterError unless 0 <= tau <= kMaxCounter.
    void set_counter(std::uint32_t v, double tau);

    // The clock: the number of decay() calls so far.
    std::uint64_t now() const { return now_; }
    // The stamp of the latest signal or addition so far (0 before the first): those made after
    // this call get larger stamps. O(1).
    std::uint64_t mark() const { return stamps_ >> kEpochBits; }
    // mark() as it was at the latest decay() (0 before the first): the stamp of the latest
    // signal or addition made before the clock came to read now(). It marks a time rather than
    // an event: collect_inactive(clock_mark()) spares every vertex signalled or added since the
    // clock came to read this value, also those signalled before this call. O(1).
    std::uint64_t clock_mark() const { return clock_mark_ >> kEpochBits; }
    // The stamp of v's last signal, or of its add() if it has never been signalled: larger is
    // later. Precondition: contains(v).
    std::uint64_t last_stamp(std::uint32_t v) const {
        assert(contains(v));
        return stamp(nodes_[v]);
    }

    // The vertex with the largest counter, ties going to the smaller id; kNone when empty.
    // Cost: O(1) plus the vertices whose counters are within a factor 2^(1/8) of the largest (its
    // bucket) — a handful in the learning loop. When every counter is below 2.2e-308 (no signal
    // for a very long time) all vertices are compared: O(largest id).
    std::uint32_t most_active() const;

    // Appends to `out` every vertex whose last stamp is <= mark (not signalled since mark was
    // taken), oldest first. O(largest id + k log k) for k vertices appended.
    void collect_inactive(std::uint64_t mark, std::vector<std::uint32_t>& out) const;

    std::size_t size() const { return size_; }
    // Starts loading v's record into the cache, ahead of a signal(v) (a hint; changes nothing).
    void prefetch(std::uint32_t v) const { prefetch_for_read(&nodes_[v]); }
    bool contains(std::uint32_t v) const { return v < nodes_.size() && nodes_[v].bucket_next != kNone; }
    double alpha() const { return alpha_; }

private:
    friend struct ActivityIndexTestAccess;  // the tests set stamps_ near kMaxStamp, check the lists

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
    // A record's word: stamp << kEpochBits | epoch mod 2^kEpochBits.
    static constexpr int kEpochBits = 16;
    static constexpr std::uint64_t kEpochMask = (std::uint64_t(1) << kEpochBits) - 1;
    static constexpr std::uint64_t kStampUnit = std::uint64_t(1) << kEpochBits;  // one stamp, in place
    // The last stamp: stamps_ + kStampUnit carries past it (next_stamps).
    static constexpr std::uint64_t kMaxStamp = ~std::uint64_t(0) >> kEpochBits;
    // A record that lags this many epochs reads as 0 and is retired (rescale, bucket_key).
    static constexpr std::uint64_t kGoneLag = 4;
    // Every kSweepEpochs epochs, the records that lag kGoneLag or more are brought to kGoneLag,
    // so that lags stay at most kSweepEpochs + kGoneLag, below 2^kEpochBits (sweep_lagging).
    static constexpr std::uint64_t kSweepEpochs = std::uint64_t(1) << (kEpochBits - 1);
    static_assert(kSweepEpochs + kGoneLag <= kEpochMask, "lags must stay below 2^kEpochBits");

    struct Node {
        double raw = 0.0;                                        // tau * scale, in the units of its epoch
        std::uint64_t stamp_epoch = 0;                           // the stamp of the last signal (or addition), and the
                                                                 // epoch raw was written in, mod 2^kEpochBits
        std::uint32_t bucket_prev = kNone, bucket_next = kNone;  // circular bucket list; kNone: absent
                                                                 // (stale, never followed, if retired)
    };
    static_assert(sizeof(Node) == 24, "a record is 24 bytes per vertex");

    static std::uint64_t stamp(const Node& n) { return n.stamp_epoch >> kEpochBits; }
    // stamps_ advanced by one stamp. Throws (changing nothing) past kMaxStamp, where the 64-bit
    // addition would carry: a branch never taken.
    std::uint64_t next_stamps() const {
        if (stamps_ > ~std::uint64_t(0) - kStampUnit) stamps_exhausted();
        return stamps_ + kStampUnit;
    }
    // How many epochs ago raw was written: exact, as lags stay below 2^kEpochBits.
    std::uint64_t lag(const Node& n) const { return (epoch_ - n.stamp_epoch) & kEpochMask; }
    // raw, rescaled to the current epoch: exact (a power-of-two scaling) unless it underflows.
    double current_raw(const Node& n) const {
        const std::uint64_t epochs = lag(n);
        return epochs == 0 ? n.raw : rescale(n.raw, epochs);
    }
    // A value written `epochs` epochs ago, times 2^(-kScaleBits * epochs). Stored values are
    // below 2^1011, so after kGoneLag = 4 epochs (2^-2048) nothing is left.
    static double rescale(double raw, std::uint64_t epochs) {
        constexpr double kDown = 0x1p-512;  // 2^-kScaleBits, exact
        if (epochs >= kGoneLag) return 0.0;
        for (; epochs > 0; --epochs) raw *= kDown;
        return raw;
    }
    // The key of a stored value written `lag` epochs ago. Below epoch_ * kEpochKeys (retired)
    // whenever the lag is kGoneLag or more: the top 15 bits of a stored value are below
    // 16384 = kGoneLag * kEpochKeys.
    std::uint64_t key(double raw, std::uint64_t lag) const {
        std::uint64_t bits;
        std::memcpy(&bits, &raw, sizeof bits);
        return (bits >> kMantissaShift) + (epoch_ - lag) * kEpochKeys;
    }
    std::uint64_t bucket_key(const Node& n) const { return key(n.raw, lag(n)); }
    void move_to_bucket(std::uint32_t v, std::uint64_t old_key, std::uint64_t new_key);
    void link_bucket(std::uint32_t v, std::uint64_t key);
    void unlink_bucket(std::uint32_t v, std::uint64_t key);
    std::uint32_t best_in_list(std::uint32_t head) const;
    void begin_epoch();
    void sweep_lagging();
    [[noreturn]] static void stamps_exhausted();
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
    std::uint64_t stamps_ = 0;      // the last stamp given, << kEpochBits (its place in a record)
    std::uint64_t clock_mark_ = 0;  // stamps_ at the latest decay()
};

}  // namespace nmesh
