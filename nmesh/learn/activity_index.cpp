#include "nmesh/learn/activity_index.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "nmesh/error.h"

namespace nmesh {

namespace {

int highest_bit(std::uint64_t word) { return 63 - __builtin_clzll(word); }
int lowest_bit(std::uint64_t word) { return __builtin_ctzll(word); }

// c ? a : b by a mask, for selections whose condition is a coin toss (written as a conditional
// expression, they were compiled into branches).
std::uint32_t pick(bool c, std::uint32_t a, std::uint32_t b) {
    const std::uint32_t mask = 0u - std::uint32_t(c);
    return (a & mask) | (b & ~mask);
}

}  // namespace

ActivityIndex::ActivityIndex(double alpha) : alpha_(alpha), inv_alpha_(1.0 / alpha), bucket_heads_(kBuckets, kNone) {
    if (!(alpha >= kMinAlpha && alpha <= 1.0))
        throw ParameterError("alpha", "ActivityIndex: alpha must be in [1e-100, 1], got " + std::to_string(alpha));
}

void ActivityIndex::reserve(std::size_t n) {
    if (n > nodes_.size()) nodes_.resize(n);
}

void ActivityIndex::shrink_ids(std::size_t n) {
    if (n < nodes_.size()) nodes_.resize(n);
    nodes_.shrink_to_fit();
}

double ActivityIndex::checked_counter(double tau, const char* what) {
    if (!(tau >= 0.0 && tau <= kMaxCounter))
        throw ParameterError("counter", std::string("ActivityIndex::") + what + ": counter must be in [0, 1e150], got " +
                             std::to_string(tau));
    return tau;
}

void ActivityIndex::stamps_exhausted() {
    throw InputError("ActivityIndex: more than 2^48 - 1 signals and additions (the stamps are exhausted)");
}

// --- vertices ------------------------------------------------------------------------------

void ActivityIndex::add(std::uint32_t v, double tau) {
    assert(v != kNone && !contains(v));
    checked_counter(tau, "add");
    const std::uint64_t stamps = next_stamps();
    if (v >= nodes_.size()) nodes_.resize(std::max<std::size_t>(std::size_t(v) + 1, 2 * nodes_.size()));
    Node& n = nodes_[v];
    n.raw = tau * scale_;
    n.stamp_epoch = stamps | (epoch_ & kEpochMask);
    stamps_ = stamps;
    link_bucket(v, bucket_key(n));
    ++size_;
}

void ActivityIndex::remove(std::uint32_t v) {
    assert(contains(v));
    Node& n = nodes_[v];
    unlink_bucket(v, bucket_key(n));
    n = Node{};
    --size_;
}

void ActivityIndex::set_counter(std::uint32_t v, double tau) {
    assert(contains(v));
    checked_counter(tau, "set_counter");
    Node& n = nodes_[v];
    const std::uint64_t old_key = bucket_key(n);
    n.raw = tau * scale_;
    n.stamp_epoch = (n.stamp_epoch & ~kEpochMask) | (epoch_ & kEpochMask);
    const std::uint64_t new_key = bucket_key(n);
    if (new_key != old_key) move_to_bucket(v, old_key, new_key);
}

// --- buckets -------------------------------------------------------------------------------
//
// A key k >= epoch_ * kEpochKeys is the bucket list bucket_heads_[k mod kBuckets], with bit
// k - epoch_ * kEpochKeys in bucket_bits_. A smaller key means the vertex is retired: it is in no
// list (its list links are stale and never followed), which spares the signal that revives it
// the unlinking, and an epoch the relinking.

void ActivityIndex::move_to_bucket(std::uint32_t v, std::uint64_t old_key, std::uint64_t new_key) {
    unlink_bucket(v, old_key);
    link_bucket(v, new_key);
}

// Both without branches on the list's shape: whether a bucket is empty, or a vertex alone in its
// own, is a coin toss when the counters move from bucket to bucket at every signal, and the
// mispredictions cost more than the few stores done either way. An empty list is linked as if
// its head were v itself, and a vertex alone is unlinked as if it had neighbours (itself).
void ActivityIndex::link_bucket(std::uint32_t v, std::uint64_t key) {
    const std::uint64_t bit = key - epoch_ * kEpochKeys;  // written in this epoch: within the window
    assert(key >= epoch_ * kEpochKeys && bit < kBuckets);
    std::uint32_t& head = bucket_heads_[key % kBuckets];
    const bool empty = head == kNone;
    const std::uint32_t next = pick(empty, v, head);
    const std::uint32_t prev = pick(empty, v, nodes_[next].bucket_prev);
    Node& n = nodes_[v];
    n.bucket_prev = prev;
    n.bucket_next = next;
    nodes_[prev].bucket_next = v;
    nodes_[next].bucket_prev = v;
    head = next;
    bucket_bits_[bit / 64] |= std::uint64_t(1) << (bit % 64);
    summary_bits_[bit / 4096] |= std::uint64_t(1) << (bit / 64 % 64);
}

void ActivityIndex::unlink_bucket(std::uint32_t v, std::uint64_t key) {
    const std::uint64_t base = epoch_ * kEpochKeys;
    if (key < base) return;  // retired: in no list
    std::uint32_t& head = bucket_heads_[key % kBuckets];
    const Node& n = nodes_[v];
    const std::uint32_t prev = n.bucket_prev, next = n.bucket_next;
    const bool alone = next == v;
    nodes_[prev].bucket_next = next;
    nodes_[next].bucket_prev = prev;
    // A head that was v becomes its successor, or kNone when v was alone.
    head = pick(head == v, pick(alone, kNone, next), head);
    // The bucket empties when v was alone.
    const std::uint64_t bit = key - base;
    std::uint64_t& word = bucket_bits_[bit / 64];
    word &= ~(std::uint64_t(alone) << (bit % 64));
    summary_bits_[bit / 4096] &= ~(std::uint64_t(word == 0) << (bit / 64 % 64));
}

// The scale is divided by 2^kScaleBits, so every stored key drops by kEpochKeys relative to the
// window: the buckets of the lowest kEpochKeys keys (the first summary word) are dropped — their
// vertices retire — and the bitmaps shift down by that much. O(1): at most 4096 buckets, found
// through 64 bitmap words; and once every kSweepEpochs epochs, O(largest id) (sweep_lagging).
void ActivityIndex::begin_epoch() {
    scale_ = std::ldexp(scale_, -kScaleBits);
    const std::uint64_t base = epoch_ * kEpochKeys;
    constexpr std::size_t kRetiredWords = kEpochKeys / 64;
    static_assert(kRetiredWords == 64, "an epoch retires exactly one summary word");
    for (std::uint64_t words = summary_bits_[0]; words != 0; words &= words - 1) {
        const std::size_t w = std::size_t(lowest_bit(words));
        for (std::uint64_t bits = bucket_bits_[w]; bits != 0; bits &= bits - 1)
            bucket_heads_[(base + w * 64 + std::uint64_t(lowest_bit(bits))) % kBuckets] = kNone;
    }
    for (std::size_t w = 0; w + kRetiredWords < kWords; ++w) bucket_bits_[w] = bucket_bits_[w + kRetiredWords];
    for (std::size_t w = kWords - kRetiredWords; w < kWords; ++w) bucket_bits_[w] = 0;
    for (std::size_t s = 0; s + 1 < kSummaryWords; ++s) summary_bits_[s] = summary_bits_[s + 1];
    summary_bits_[kSummaryWords - 1] = 0;
    ++epoch_;
    if (epoch_ % kSweepEpochs == 0) sweep_lagging();
}

// Records keep their epoch mod 2^kEpochBits, which gives their lag right only below
// 2^kEpochBits epochs. Those that lag kGoneLag or more (the retired vertices not signalled for
// that long, up to all of them) read as 0 and are in no list, whatever their raw: rewritten to
// lag exactly kGoneLag, they still read as 0 and are still retired (key below
// epoch_ * kEpochKeys: see bucket_key), raw and stamp unchanged, and their lag cannot reach
// 2^kEpochBits before the next sweep, kSweepEpochs epochs later. Free slots (Node{}) are
// rewritten too, harmlessly: add() overwrites them. O(largest id), once every kSweepEpochs
// epochs.
void ActivityIndex::sweep_lagging() {
    const std::uint64_t gone_epoch = (epoch_ - kGoneLag) & kEpochMask;
    for (Node& n : nodes_)
        if (lag(n) >= kGoneLag) n.stamp_epoch = (n.stamp_epoch & ~kEpochMask) | gone_epoch;
}

// --- queries -------------------------------------------------------------------------------

std::uint32_t ActivityIndex::best_in_list(std::uint32_t head) const {
    std::uint32_t best = head;
    double best_raw = current_raw(nodes_[head]);
    for (std::uint32_t v = nodes_[head].bucket_next; v != head; v = nodes_[v].bucket_next) {
        const double raw = current_raw(nodes_[v]);
        if (raw > best_raw || (raw == best_raw && v < best)) {
            best = v;
            best_raw = raw;
        }
    }
    return best;
}

std::uint32_t ActivityIndex::most_active() const {
    if (size_ == 0) return kNone;
    for (std::size_t s = kSummaryWords; s-- > 0;) {
        if (summary_bits_[s] == 0) continue;
        const std::size_t w = s * 64 + std::size_t(highest_bit(summary_bits_[s]));
        const std::uint64_t bit = w * 64 + std::uint64_t(highest_bit(bucket_bits_[w]));
        return best_in_list(bucket_heads_[(epoch_ * kEpochKeys + bit) % kBuckets]);
    }
    // Every vertex is retired (all counters below 2.2e-308): compare them all, in id order.
    std::uint32_t best = kNone;
    double best_raw = -1.0;
    for (std::uint32_t v = 0; v < nodes_.size(); ++v) {
        if (!contains(v)) continue;
        const double raw = current_raw(nodes_[v]);
        if (raw > best_raw) {
            best = v;
            best_raw = raw;
        }
    }
    return best;
}

void ActivityIndex::collect_inactive(std::uint64_t mark, std::vector<std::uint32_t>& out) const {
    const std::size_t first = out.size();
    for (std::uint32_t v = 0; v < nodes_.size(); ++v)
        if (contains(v) && stamp(nodes_[v]) <= mark) out.push_back(v);
    // Every stamp is given once, so the vertices' stamps differ: the order is total.
    std::sort(out.begin() + std::ptrdiff_t(first), out.end(),
              [&](std::uint32_t a, std::uint32_t b) { return stamp(nodes_[a]) < stamp(nodes_[b]); });
}

}  // namespace nmesh
