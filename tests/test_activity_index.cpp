// ActivityIndex: every answer is compared with a naive reference (plain arrays, O(n) decay,
// O(n) maximum, O(n) scan for inactive vertices, by stamp and by time).
//
// Tolerance: counters agree within a relative 1e-9 plus an absolute 1e-300. Both sides multiply
// by alpha (or 1/alpha) once per decay, each with a rounding of 2^-53, so after the 10^6 decays of
// these runs they may differ by about 1e-10 relative; below the smallest normal double (2.2e-308)
// both lose relative precision, hence the absolute term.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <tuple>
#include <vector>

#include "error_fixtures.h"
#include "nmesh/learn/activity_index.h"
#include "nmesh/error.h"
#include "nmesh/util/random.h"

using nmesh::ActivityIndex;
using nmesh::Random;

namespace nmesh {

// Reaches the index's insides: the stamp counter, to test the stamps' limit without 2^48
// signals, and the bucket lists, to check them against the records.
struct ActivityIndexTestAccess {
    static constexpr std::uint64_t kMaxStamp = ActivityIndex::kMaxStamp;
    static void set_stamps(ActivityIndex& index, std::uint64_t stamps) {
        index.stamps_ = stamps << ActivityIndex::kEpochBits;
    }

    // Every vertex whose bucket key is in the window (not retired) is in the list of its key and
    // in no other; the lists are circular and doubly linked; the bitmaps mark exactly the
    // non-empty lists. O(largest id + kBuckets).
    static void check_buckets(const ActivityIndex& index) {
        constexpr std::size_t kBuckets = ActivityIndex::kBuckets;
        const std::uint64_t base = index.epoch_ * ActivityIndex::kEpochKeys;
        std::size_t listed = 0;
        for (std::size_t bit = 0; bit < kBuckets; ++bit) {
            const std::uint32_t head = index.bucket_heads_[(base + bit) % kBuckets];
            const std::uint64_t word = index.bucket_bits_[bit / 64];
            const bool marked = ((word >> (bit % 64)) & 1) != 0;
            const bool summarised = ((index.summary_bits_[bit / 4096] >> (bit / 64 % 64)) & 1) != 0;
            if (marked != (head != ActivityIndex::kNone) || summarised != (word != 0)) {  // REQUIRE is slow
                INFO("bucket " << bit << " of the window");
                REQUIRE(marked == (head != ActivityIndex::kNone));
                REQUIRE(summarised == (word != 0));
            }
            if (head == ActivityIndex::kNone) continue;
            std::uint32_t v = head;
            do {
                INFO("vertex " << v << " in the list of key " << base + bit);
                REQUIRE(index.contains(v));
                REQUIRE(index.bucket_key(index.nodes_[v]) == base + bit);
                REQUIRE(index.nodes_[index.nodes_[v].bucket_next].bucket_prev == v);
                REQUIRE(++listed <= index.size());
                v = index.nodes_[v].bucket_next;
            } while (v != head);
        }
        std::size_t live = 0;
        for (std::uint32_t v = 0; v < index.nodes_.size(); ++v)
            live += index.contains(v) && index.bucket_key(index.nodes_[v]) >= base;
        REQUIRE(listed == live);
    }
};

}  // namespace nmesh

namespace {

constexpr std::uint32_t kNone = ActivityIndex::kNone;

double tolerance(double a, double b) { return 1e-9 * std::max(std::fabs(a), std::fabs(b)) + 1e-300; }
bool close(double a, double b) { return std::fabs(a - b) <= tolerance(a, b); }

struct Reference {
    double alpha;
    std::uint64_t now = 0;
    std::uint64_t stamp = 0;       // signals and adds so far: the last stamp given
    std::uint64_t clock_mark = 0;  // stamp at the latest decay
    std::vector<double> tau;
    std::vector<char> alive;
    std::vector<std::uint64_t> last, order;  // time and stamp of the last signal (or add)
    std::vector<std::uint32_t> ids;          // alive ids

    explicit Reference(double a) : alpha(a) {}
    bool contains(std::uint32_t v) const { return v < alive.size() && alive[v]; }
    void add(std::uint32_t v, double t) {
        if (v >= alive.size()) {
            tau.resize(v + 1);
            alive.resize(v + 1, 0);
            last.resize(v + 1);
            order.resize(v + 1);
        }
        alive[v] = 1;
        tau[v] = t;
        last[v] = now;
        order[v] = ++stamp;
        ids.push_back(v);
    }
    void remove(std::uint32_t v) {
        alive[v] = 0;
        ids.erase(std::find(ids.begin(), ids.end(), v));
    }
    void signal(std::uint32_t v) {
        tau[v] += 1.0;
        last[v] = now;
        order[v] = ++stamp;
    }
    void decay() {
        for (std::uint32_t v : ids) tau[v] *= alpha;
        clock_mark = stamp;
        ++now;
    }
    // Not signalled (nor added) since `mark` was the last stamp given.
    std::vector<std::uint32_t> inactive_at_mark(std::uint64_t mark) const {
        std::vector<std::uint32_t> out;
        for (std::uint32_t v : ids)
            if (order[v] <= mark) out.push_back(v);
        std::sort(out.begin(), out.end(), [&](std::uint32_t a, std::uint32_t b) { return order[a] < order[b]; });
        return out;
    }
    // Not signalled (nor added) since the clock read `since`; equal times in event order.
    std::vector<std::uint32_t> inactive_at_time(std::uint64_t since) const {
        std::vector<std::uint32_t> out;
        for (std::uint32_t v : ids)
            if (last[v] < since) out.push_back(v);
        std::sort(out.begin(), out.end(), [&](std::uint32_t a, std::uint32_t b) {
            return std::tie(last[a], order[a]) < std::tie(last[b], order[b]);
        });
        return out;
    }
};

// The index, its reference, and the index's clock_mark() at every time so far.
struct Pair {
    ActivityIndex index;
    Reference ref;
    std::vector<std::uint64_t> clock_marks{0};  // clock_marks[t]: clock_mark() when now() was t

    explicit Pair(double alpha) : index(alpha), ref(alpha) {}
    void decay() {
        index.decay();
        ref.decay();
        clock_marks.push_back(index.clock_mark());
    }
    void signal(std::uint32_t v) {
        index.signal(v);
        ref.signal(v);
    }
};

void check_counter(const ActivityIndex& index, const Reference& ref, std::uint32_t v) {
    const double got = index.counter(v), expected = ref.tau[v];
    if (!close(got, expected)) {
        INFO("vertex " << v << " at time " << ref.now);
        CHECK(got == doctest::Approx(expected));
        REQUIRE(close(got, expected));
    }
}

// most_active must return a vertex whose counter is the maximum within the tolerance, and the
// very vertex when the maximum is unique by more than the tolerance.
void check_most_active(const ActivityIndex& index, const Reference& ref) {
    const std::uint32_t got = index.most_active();
    if (ref.ids.empty()) {
        REQUIRE(got == kNone);
        return;
    }
    std::uint32_t best = kNone;
    double max = -1.0, second = -1.0;
    for (std::uint32_t v : ref.ids) {
        if (ref.tau[v] > max || (ref.tau[v] == max && v < best)) {
            second = std::max(second, max);
            max = ref.tau[v];
            best = v;
        } else {
            second = std::max(second, ref.tau[v]);
        }
    }
    REQUIRE(ref.contains(got));
    INFO("got " << got << " (" << ref.tau[got] << "), expected " << best << " (" << max << ") at time " << ref.now);
    REQUIRE(close(ref.tau[got], max));
    if (max - second > 2 * tolerance(max, second)) REQUIRE(got == best);
}

void check_inactive(const ActivityIndex& index, std::uint64_t mark, std::vector<std::uint32_t> expected) {
    std::vector<std::uint32_t> got{12345};  // collect_inactive appends: keep what was there
    index.collect_inactive(mark, got);
    expected.insert(expected.begin(), 12345);
    INFO("mark " << mark);
    REQUIRE(got == expected);
}

// The marks and stamps agree with the reference's count of events, and collect_inactive agrees
// at the marks given (taken earlier) and, through the clock marks, at every given time: a vertex
// not signalled since time t is one whose stamp is <= the mark of the decay that began t.
void check_inactive(const Pair& p, const std::vector<std::uint64_t>& marks, const std::vector<std::uint64_t>& times) {
    REQUIRE(p.index.mark() == p.ref.stamp);
    REQUIRE(p.index.clock_mark() == p.ref.clock_mark);
    for (std::uint32_t v : p.ref.ids) REQUIRE(p.index.last_stamp(v) == p.ref.order[v]);
    for (std::uint64_t mark : marks) check_inactive(p.index, mark, p.ref.inactive_at_mark(mark));
    for (std::uint64_t t : times) {
        INFO("since time " << t << " (now " << p.ref.now << ")");
        check_inactive(p.index, p.clock_marks[t], p.ref.inactive_at_time(t));
    }
}

// Counters spanning the accepted range, so that buckets far apart are used.
double random_counter(Random& rng) {
    switch (rng.below(6)) {
        case 0:
            return 0.0;
        case 1:
            return 1e-200 * rng.uniform();
        case 2:
            return 1e100 * rng.uniform();
        default:
            return 20.0 * rng.uniform();
    }
}

// A random run of `steps` events, decays being frequent; every `stretch_every` steps a long
// stretch of `stretch` decays with a few signals, so that many epochs pass (renormalisation).
void run_random_sequence(double alpha, std::uint64_t seed, int steps, std::uint32_t max_vertices, int stretch_every,
                         int stretch) {
    Random rng(seed);
    Pair p(alpha);
    ActivityIndex& index = p.index;
    Reference& ref = p.ref;
    std::vector<std::uint32_t> free_ids;
    std::uint32_t next_id = 0;
    std::vector<std::uint64_t> marks{0};  // marks taken along the way
    auto pick = [&] { return ref.ids[rng.below(std::uint32_t(ref.ids.size()))]; };
    // Marks to query: a few taken along the way, an arbitrary value, the current ones; times:
    // recent and old ones, and now (the clock mark).
    auto query = [&](std::uint64_t span) {
        std::vector<std::uint64_t> some{
            marks[marks.size() - 1 - rng.below(std::uint32_t(std::min<std::size_t>(marks.size(), 20)))],
            marks[rng.below(std::uint32_t(marks.size()))], std::uint64_t(rng.below(std::uint32_t(ref.stamp + 1))),
            index.mark(), index.clock_mark()};
        std::vector<std::uint64_t> times{ref.now};
        for (std::uint64_t back : {std::uint64_t(rng.below(20)), std::uint64_t(rng.below(std::uint32_t(span))) + 1})
            times.push_back(ref.now >= back ? ref.now - back : 0);
        check_inactive(p, some, times);
        nmesh::ActivityIndexTestAccess::check_buckets(index);
    };
    for (int step = 1; step <= steps; ++step) {
        const std::uint32_t op = rng.below(100);
        if (ref.ids.size() < 2 || (op < 8 && ref.ids.size() < max_vertices)) {
            std::uint32_t v;
            if (!free_ids.empty() && rng.below(3) != 0) {
                v = free_ids.back();
                free_ids.pop_back();
            } else {
                v = next_id++;
            }
            const double t = rng.below(2) == 0 ? 0.0 : random_counter(rng);
            index.add(v, t);
            ref.add(v, t);
            REQUIRE(index.contains(v));
            REQUIRE(index.last_stamp(v) == index.mark());
            check_counter(index, ref, v);
        } else if (op < 14) {
            const std::uint32_t v = pick();
            index.remove(v);
            ref.remove(v);
            free_ids.push_back(v);
            REQUIRE_FALSE(index.contains(v));
        } else if (op < 40) {
            // Signals favour a few vertices, as winners do on a learning mesh.
            const std::uint32_t v = rng.below(2) == 0
                                        ? ref.ids[rng.below(std::min<std::uint32_t>(3, std::uint32_t(ref.ids.size())))]
                                        : pick();
            p.signal(v);
            REQUIRE(index.last_stamp(v) == ref.order[v]);
            check_counter(index, ref, v);
        } else if (op < 44) {
            const std::uint32_t v = pick();
            const double t = random_counter(rng);
            index.set_counter(v, t);
            ref.tau[v] = t;
            check_counter(index, ref, v);
        } else if (op < 88) {
            p.decay();
            REQUIRE(index.now() == ref.now);
        } else if (op < 90) {
            marks.push_back(index.mark());
        } else if (op < 96) {
            check_most_active(index, ref);
        } else {
            query(2000);
        }
        REQUIRE(index.size() == ref.ids.size());
        if (step % 64 == 0)
            for (std::uint32_t v : ref.ids) check_counter(index, ref, v);
        if (step % stretch_every == 0) {
            marks.push_back(index.mark());
            for (int k = 0; k < stretch; ++k) {
                p.decay();
                if (k % 499 == 0) p.signal(pick());
                if (k % 9973 == 0) check_most_active(index, ref);
            }
            for (std::uint32_t v : ref.ids) check_counter(index, ref, v);
            check_most_active(index, ref);
            query(std::uint64_t(stretch) * 2);
        }
    }
}

}  // namespace

TEST_CASE("ActivityIndex: signal, decay, the clock and the stamps follow eqs. (6)-(7)") {
    ActivityIndex index(0.5);
    CHECK(index.most_active() == kNone);
    CHECK(index.mark() == 0);
    index.add(3);       // stamp 1
    index.add(1, 4.0);  // stamp 2
    CHECK(index.size() == 2);
    CHECK(index.counter(3) == 0.0);
    CHECK(index.counter(1) == 4.0);
    CHECK(index.last_stamp(3) == 1);
    index.signal(3);  // stamp 3
    CHECK(index.counter(3) == 1.0);
    CHECK(index.clock_mark() == 0);
    index.decay();
    index.decay();
    CHECK(index.now() == 2);
    CHECK(index.counter(3) == 0.25);
    CHECK(index.counter(1) == 1.0);
    CHECK(index.last_stamp(3) == 3);
    CHECK(index.mark() == 3);
    CHECK(index.clock_mark() == 3);
    index.signal(3);
    CHECK(index.counter(3) == 1.25);
    CHECK(index.last_stamp(3) == 4);
    CHECK(index.mark() == 4);
    CHECK(index.clock_mark() == 3);  // the mark of the latest decay
    CHECK(index.most_active() == 3);
    index.set_counter(1, 7.0);
    CHECK(index.most_active() == 1);
    CHECK(index.last_stamp(1) == 2);  // set_counter is not a signal
    CHECK(index.mark() == 4);
    index.remove(1);
    CHECK_FALSE(index.contains(1));
    CHECK(index.most_active() == 3);
}

TEST_CASE("ActivityIndex: equal counters go to the smaller id, including all-zero counters") {
    ActivityIndex index(0.9);
    for (std::uint32_t v : {8u, 5u, 6u, 2u, 9u}) index.add(v, 3.0);
    index.set_counter(2, 1.0);
    CHECK(index.most_active() == 5);
    index.set_counter(9, 3.5);
    CHECK(index.most_active() == 9);
    index.remove(9);
    index.remove(5);
    CHECK(index.most_active() == 6);

    // After enough decays every counter underflows to 0: a five-way tie.
    ActivityIndex zero(0.5);
    for (std::uint32_t v : {8u, 5u, 6u, 7u, 9u}) zero.add(v, 1.0 + v);
    for (int i = 0; i < 5000; ++i) zero.decay();
    CHECK(zero.counter(9) == 0.0);
    CHECK(zero.most_active() == 5);
    zero.signal(9);
    CHECK(zero.most_active() == 9);
    CHECK(zero.counter(9) == 1.0);
}

TEST_CASE("ActivityIndex: a million decays renormalise the scale without losing a counter") {
    // Without renormalisation the scale 0.999^-t would overflow after about 710,000 decays.
    ActivityIndex index(0.999);
    index.add(0, 5.0);
    index.add(1);
    for (int i = 0; i < 1000000; ++i) {
        index.decay();
        if (i == 49999) CHECK(index.counter(0) == doctest::Approx(5.0 * std::pow(0.999, 50000)).epsilon(1e-9));
        if (i % 100000 == 99999) index.signal(1);
    }
    CHECK(index.now() == 1000000);
    // Vertex 1's earlier signals have decayed by 0.999^100000 = 3.6e-44: its counter rounds to 1.
    CHECK(index.counter(1) == doctest::Approx(1.0).epsilon(1e-12));
    CHECK(index.counter(0) == 0.0);  // 5 * 0.999^1e6 underflows
    CHECK(index.most_active() == 1);
    index.signal(0);
    CHECK(index.counter(0) == doctest::Approx(1.0).epsilon(1e-12));
    CHECK(index.most_active() == 0);  // a tie at 1.0 goes to the smaller id
    index.signal(1);
    CHECK(index.most_active() == 1);
    CHECK(index.counter(1) == doctest::Approx(2.0).epsilon(1e-12));
}

TEST_CASE("ActivityIndex: collect_inactive lists by last signal, oldest first") {
    ActivityIndex index(0.95);
    index.add(4);
    index.add(2);
    const std::uint64_t after_adds = index.mark();
    index.decay();  // t = 1
    const std::uint64_t t1 = index.clock_mark();
    index.add(7);
    index.signal(4);
    index.decay();  // t = 2
    const std::uint64_t t2 = index.clock_mark();
    index.signal(2);
    CHECK(after_adds == t1);
    std::vector<std::uint32_t> out;
    index.collect_inactive(0, out);
    CHECK(out.empty());
    index.collect_inactive(t1, out);  // 4 and 2 have been signalled since
    CHECK(out.empty());
    index.collect_inactive(t2, out);
    CHECK(out == std::vector<std::uint32_t>{7, 4});  // both at t = 1: in the order they happened
    index.collect_inactive(t2 - 1, out);             // appends: 7 alone, added just before 4's signal
    CHECK(out == std::vector<std::uint32_t>{7, 4, 7});
    out.clear();
    index.collect_inactive(index.mark(), out);
    CHECK(out == std::vector<std::uint32_t>{7, 4, 2});
    index.remove(4);
    out.clear();
    index.collect_inactive(100, out);
    CHECK(out == std::vector<std::uint32_t>{7, 2});
}

TEST_CASE("ActivityIndex: vertices idle for over 2^16 epochs read 0 and come back") {
    // At the smallest alpha an epoch comes every 1.5 decays, so 2^16 epochs pass in about 100,000
    // decays and the records' 16-bit epochs wrap around several times. Every counter is compared
    // with the reference after every decay: a record whose lag were read modulo 2^16 after 2^16
    // epochs would read as written in a recent epoch (not 0) at some decay, and a signal would
    // then unlink it from a list it is not in; the bucket lists are checked against the records.
    // Vertices come back after idling for random stretches (about one signal in seven after more
    // than 2^16 epochs), a few never do, slots are removed and reused, and counters are set up
    // to 1e100 (stored values up to 2^844, whose keys are high in their epoch's window).
    Random rng(7);
    Pair p(ActivityIndex::kMinAlpha);
    std::vector<std::uint64_t> marks{0};
    std::vector<std::uint32_t> free_ids;
    for (std::uint32_t v = 0; v < 40; ++v) {
        const double t = random_counter(rng);
        p.index.add(v, t);
        p.ref.add(v, t);
    }
    const std::uint32_t never = 3;  // vertices 0-2: never signalled
    std::uint32_t next_id = 40;
    const int decays = 400000;
    for (int k = 1; k <= decays; ++k) {
        p.decay();
        if (rng.below(4) == 0) p.signal(never + rng.below(2));  // 3 and 4: busy
        if (rng.below(2500) == 0) {
            const std::uint32_t v = p.ref.ids[never + 2 + rng.below(std::uint32_t(p.ref.ids.size()) - never - 2)];
            p.signal(v);  // a come-back, or a frequent winner (one in 2,500 decays among ~35)
            check_counter(p.index, p.ref, v);
            check_most_active(p.index, p.ref);
            nmesh::ActivityIndexTestAccess::check_buckets(p.index);
        }
        if (rng.below(20000) == 0) {  // a removal, and an addition into a free slot or a new one
            const std::uint32_t v = p.ref.ids[never + 2 + rng.below(std::uint32_t(p.ref.ids.size()) - never - 2)];
            p.index.remove(v);
            p.ref.remove(v);
            free_ids.push_back(v);
            std::uint32_t w = next_id;
            if (rng.below(2) == 0) {
                w = free_ids.front();  // the oldest free slot (perhaps v's)
                free_ids.erase(free_ids.begin());
            } else {
                ++next_id;
            }
            const double t = random_counter(rng);
            p.index.add(w, t);
            p.ref.add(w, t);
        }
        if (rng.below(5000) == 0) {  // a stored value up to 1e100 * 2^512: keys high in the window
            const std::uint32_t v = p.ref.ids[never + 2 + rng.below(std::uint32_t(p.ref.ids.size()) - never - 2)];
            const double t = random_counter(rng);
            p.index.set_counter(v, t);
            p.ref.tau[v] = t;
        }
        for (std::uint32_t v : p.ref.ids) check_counter(p.index, p.ref, v);
        if (k % 1000 == 0) {
            check_most_active(p.index, p.ref);
            nmesh::ActivityIndexTestAccess::check_buckets(p.index);
        }
        if (k % 10000 == 0) marks.push_back(p.index.mark());
        if (k % 50000 == 0) {
            std::vector<std::uint64_t> times;
            for (std::uint64_t t = 0; t <= p.ref.now; t += 25000) times.push_back(t);
            check_inactive(p, marks, times);
        }
    }
    for (std::uint32_t v = 0; v < never; ++v) {
        REQUIRE(p.index.counter(v) == 0.0);
        p.signal(v);
        check_counter(p.index, p.ref, v);
    }
    check_most_active(p.index, p.ref);
    nmesh::ActivityIndexTestAccess::check_buckets(p.index);
    check_inactive(p, marks, {0, p.ref.now / 2, p.ref.now});
}

TEST_CASE("ActivityIndex: stamps are 48 bits; past the last one, signal and add throw and change nothing") {
    constexpr std::uint64_t kMaxStamp = nmesh::ActivityIndexTestAccess::kMaxStamp;
    static_assert(kMaxStamp == (std::uint64_t(1) << 48) - 1, "the documented limit");
    ActivityIndex index(0.5);
    index.add(0, 2.0);  // stamp 1
    index.add(1, 1.0);  // stamp 2
    nmesh::ActivityIndexTestAccess::set_stamps(index, kMaxStamp - 2);
    index.add(2, 0.5);  // stamp kMaxStamp - 1
    index.signal(1);    // stamp kMaxStamp: the last one; 1's counter is now 2
    CHECK(index.last_stamp(1) == kMaxStamp);
    CHECK(index.last_stamp(2) == kMaxStamp - 1);
    CHECK(index.last_stamp(0) == 1);
    CHECK(index.mark() == kMaxStamp);
    for (int i = 0; i < 3; ++i) index.decay();  // decays leave the stamps
    std::vector<std::uint32_t> out;
    index.collect_inactive(kMaxStamp - 1, out);
    CHECK(out == std::vector<std::uint32_t>{0, 2});
    index.collect_inactive(kMaxStamp, out);
    CHECK(out == std::vector<std::uint32_t>{0, 2, 0, 2, 1});

    CHECK_THROWS_AS(index.signal(0), nmesh::InputError);
    CHECK_THROWS_AS(index.add(3, 1.0), nmesh::InputError);
    CHECK_FALSE(index.contains(3));
    CHECK(index.size() == 3);
    CHECK(index.mark() == kMaxStamp);
    CHECK(index.last_stamp(0) == 1);
    CHECK(index.counter(0) == 0.25);
    CHECK(index.counter(1) == 0.25);
    CHECK(index.most_active() == 0);  // the tie at 0.25 goes to the smaller id
    index.set_counter(2, 3.0);        // not a signal: still allowed
    CHECK(index.most_active() == 2);
}

TEST_CASE("ActivityIndex: random events agree with a naive reference") {
    for (double alpha : {0.5, 0.95, 0.999, ActivityIndex::kMinAlpha}) {
        for (std::uint64_t seed = 1; seed <= 2; ++seed) {
            CAPTURE(alpha);
            CAPTURE(seed);
            // 0.999 needs ~354,000 decays per epoch: the long stretches provide them. At the
            // smallest alpha each makes ~84,000 epochs: the records' 16-bit epochs wrap around.
            const int stretch = alpha == 0.999 || alpha == ActivityIndex::kMinAlpha ? 130000 : 20000;
            run_random_sequence(alpha, seed, 12000, 120, 4000, stretch);
        }
    }
}

TEST_CASE("ActivityIndex: rejects alpha and counters out of range") {
    CHECK(nmesh::test::refused_parameter([] { ActivityIndex(0.0); }) == "alpha");
    CHECK_THROWS_AS(ActivityIndex(1.5), nmesh::ParameterError);
    CHECK_THROWS_AS(ActivityIndex(std::nan("")), nmesh::ParameterError);
    ActivityIndex no_decay(1.0);  // alpha = 1 is allowed: counters never decay
    no_decay.add(0, 2.0);
    no_decay.decay();
    CHECK(no_decay.counter(0) == 2.0);
    CHECK(nmesh::test::refused_parameter([&] { no_decay.add(1, -1.0); }) == "counter");
    CHECK_THROWS_AS(no_decay.add(1, 1e200), nmesh::ParameterError);
    CHECK_THROWS_AS(no_decay.add(1, std::numeric_limits<double>::quiet_NaN()), nmesh::ParameterError);
    CHECK_FALSE(no_decay.contains(1));
    CHECK_THROWS_AS(no_decay.set_counter(0, -0.5), nmesh::ParameterError);
    CHECK(no_decay.counter(0) == 2.0);
}

TEST_CASE("ActivityIndex: a weighted signal adds its weight, decays like a unit one and ranks by it") {
    ActivityIndex a(0.95);
    a.add(1);
    a.add(2);
    a.add(3);
    a.signal(1);
    a.signal(2, 2.5);
    a.signal(3, 0.25);
    CHECK(a.counter(1) == doctest::Approx(1.0));
    CHECK(a.counter(2) == doctest::Approx(2.5));
    CHECK(a.counter(3) == doctest::Approx(0.25));
    CHECK(a.most_active() == 2);
    for (int i = 0; i < 10; ++i) a.decay();
    const double f = std::pow(0.95, 10);
    CHECK(a.counter(2) == doctest::Approx(2.5 * f));
    a.signal(1, 3.0);  // 1 * f + 3 > 2.5 * f
    CHECK(a.counter(1) == doctest::Approx(f + 3.0));
    CHECK(a.most_active() == 1);
    // A weight of 1 is the unit signal, bit for bit.
    ActivityIndex b(0.9), c(0.9);
    b.add(0);
    c.add(0);
    for (int i = 0; i < 100; ++i) {
        b.signal(0);
        c.signal(0, 1.0);
        b.decay();
        c.decay();
    }
    CHECK(b.counter(0) == c.counter(0));
}
