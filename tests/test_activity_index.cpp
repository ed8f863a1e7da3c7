// ActivityIndex: every answer is compared with a naive reference (plain arrays, O(n) decay,
// O(n) maximum, O(n) scan for inactive vertices).
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

#include "nmesh/activity_index.h"
#include "nmesh/error.h"
#include "nmesh/random.h"

using nmesh::ActivityIndex;
using nmesh::Random;

namespace {

constexpr std::uint32_t kNone = ActivityIndex::kNone;

double tolerance(double a, double b) { return 1e-9 * std::max(std::fabs(a), std::fabs(b)) + 1e-300; }
bool close(double a, double b) { return std::fabs(a - b) <= tolerance(a, b); }

struct Reference {
    double alpha;
    std::uint64_t now = 0;
    std::uint64_t stamp = 0;  // orders signals and adds made at the same time
    std::vector<double> tau;
    std::vector<char> alive;
    std::vector<std::uint64_t> last, order;
    std::vector<std::uint32_t> ids;  // alive ids

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
        order[v] = stamp++;
        ids.push_back(v);
    }
    void remove(std::uint32_t v) {
        alive[v] = 0;
        ids.erase(std::find(ids.begin(), ids.end(), v));
    }
    void signal(std::uint32_t v) {
        tau[v] += 1.0;
        last[v] = now;
        order[v] = stamp++;
    }
    void decay() {
        for (std::uint32_t v : ids) tau[v] *= alpha;
        ++now;
    }
    std::vector<std::uint32_t> inactive(std::uint64_t since) const {
        std::vector<std::uint32_t> out;
        for (std::uint32_t v : ids)
            if (last[v] < since) out.push_back(v);
        std::sort(out.begin(), out.end(), [&](std::uint32_t a, std::uint32_t b) {
            return std::tie(last[a], order[a]) < std::tie(last[b], order[b]);
        });
        return out;
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
    INFO("got " << got << " (" << ref.tau[got] << "), expected " << best << " (" << max << ") at time "
                << ref.now);
    REQUIRE(close(ref.tau[got], max));
    if (max - second > 2 * tolerance(max, second)) REQUIRE(got == best);
}

void check_inactive(const ActivityIndex& index, const Reference& ref, std::uint64_t since) {
    std::vector<std::uint32_t> got{12345};  // collect_inactive appends: keep what was there
    index.collect_inactive(since, got);
    std::vector<std::uint32_t> expected = ref.inactive(since);
    expected.insert(expected.begin(), 12345);
    REQUIRE(got == expected);
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
void run_random_sequence(double alpha, std::uint64_t seed, int steps, std::uint32_t max_vertices,
                         int stretch_every, int stretch) {
    Random rng(seed);
    ActivityIndex index(alpha);
    Reference ref(alpha);
    std::vector<std::uint32_t> free_ids;
    std::uint32_t next_id = 0;
    auto pick = [&] { return ref.ids[rng.below(std::uint32_t(ref.ids.size()))]; };
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
            REQUIRE(index.last_signal(v) == ref.now);
            check_counter(index, ref, v);
        } else if (op < 14) {
            const std::uint32_t v = pick();
            index.remove(v);
            ref.remove(v);
            free_ids.push_back(v);
            REQUIRE_FALSE(index.contains(v));
        } else if (op < 40) {
            // Signals favour a few vertices, as winners do on a learning mesh.
            const std::uint32_t v =
                rng.below(2) == 0
                    ? ref.ids[rng.below(std::min<std::uint32_t>(3, std::uint32_t(ref.ids.size())))]
                    : pick();
            index.signal(v);
            ref.signal(v);
            REQUIRE(index.last_signal(v) == ref.now);
            check_counter(index, ref, v);
        } else if (op < 44) {
            const std::uint32_t v = pick();
            const double t = random_counter(rng);
            index.set_counter(v, t);
            ref.tau[v] = t;
            check_counter(index, ref, v);
        } else if (op < 90) {
            index.decay();
            ref.decay();
            REQUIRE(index.now() == ref.now);
        } else if (op < 96) {
            check_most_active(index, ref);
        } else {
            const std::uint64_t back =
                rng.below(3) == 0 ? std::uint64_t(rng.below(20)) : std::uint64_t(rng.below(2000));
            check_inactive(index, ref, ref.now + 1 >= back ? ref.now + 1 - back : 0);
        }
        REQUIRE(index.size() == ref.ids.size());
        if (step % 64 == 0)
            for (std::uint32_t v : ref.ids) check_counter(index, ref, v);
        if (step % stretch_every == 0) {
            for (int k = 0; k < stretch; ++k) {
                index.decay();
                ref.decay();
                if (k % 499 == 0) {
                    const std::uint32_t v = pick();
                    index.signal(v);
                    ref.signal(v);
                }
                if (k % 9973 == 0) check_most_active(index, ref);
            }
            for (std::uint32_t v : ref.ids) check_counter(index, ref, v);
            check_most_active(index, ref);
            check_inactive(index, ref, ref.now - std::uint64_t(stretch) / 2);
        }
    }
}

}  // namespace

TEST_CASE("ActivityIndex: signal, decay and the clock follow eqs. (6)-(7)") {
    ActivityIndex index(0.5);
    CHECK(index.most_active() == kNone);
    index.add(3);
    index.add(1, 4.0);
    CHECK(index.size() == 2);
    CHECK(index.counter(3) == 0.0);
    CHECK(index.counter(1) == 4.0);
    index.signal(3);
    CHECK(index.counter(3) == 1.0);
    index.decay();
    index.decay();
    CHECK(index.now() == 2);
    CHECK(index.counter(3) == 0.25);
    CHECK(index.counter(1) == 1.0);
    CHECK(index.last_signal(3) == 0);
    index.signal(3);
    CHECK(index.counter(3) == 1.25);
    CHECK(index.last_signal(3) == 2);
    CHECK(index.most_active() == 3);
    index.set_counter(1, 7.0);
    CHECK(index.most_active() == 1);
    CHECK(index.last_signal(1) == 0);  // set_counter is not a signal
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
        if (i == 49999)
            CHECK(index.counter(0) == doctest::Approx(5.0 * std::pow(0.999, 50000)).epsilon(1e-9));
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
    index.decay();  // t = 1
    index.add(7);
    index.signal(4);
    index.decay();  // t = 2
    index.signal(2);
    std::vector<std::uint32_t> out;
    index.collect_inactive(1, out);
    CHECK(out.empty());
    index.collect_inactive(2, out);
    CHECK(out == std::vector<std::uint32_t>{7, 4});  // both at t = 1: in the order they happened
    out.clear();
    index.collect_inactive(3, out);
    CHECK(out == std::vector<std::uint32_t>{7, 4, 2});
    index.remove(4);
    out.clear();
    index.collect_inactive(100, out);
    CHECK(out == std::vector<std::uint32_t>{7, 2});
}

TEST_CASE("ActivityIndex: random events agree with a naive reference") {
    for (double alpha : {0.5, 0.95, 0.999}) {
        for (std::uint64_t seed = 1; seed <= 2; ++seed) {
            CAPTURE(alpha);
            CAPTURE(seed);
            // 0.999 needs ~354,000 decays per epoch: the long stretches provide them.
            const int stretch = alpha == 0.999 ? 130000 : 20000;
            run_random_sequence(alpha, seed, 12000, 120, 4000, stretch);
        }
    }
}

TEST_CASE("ActivityIndex: rejects alpha and counters out of range") {
    CHECK_THROWS_AS(ActivityIndex(0.0), nmesh::ParameterError);
    CHECK_THROWS_AS(ActivityIndex(1.5), nmesh::ParameterError);
    CHECK_THROWS_AS(ActivityIndex(std::nan("")), nmesh::ParameterError);
    ActivityIndex no_decay(1.0);  // alpha = 1 is allowed: counters never decay
    no_decay.add(0, 2.0);
    no_decay.decay();
    CHECK(no_decay.counter(0) == 2.0);
    CHECK_THROWS_AS(no_decay.add(1, -1.0), nmesh::ParameterError);
    CHECK_THROWS_AS(no_decay.add(1, 1e200), nmesh::ParameterError);
    CHECK_THROWS_AS(no_decay.add(1, std::numeric_limits<double>::quiet_NaN()), nmesh::ParameterError);
    CHECK_FALSE(no_decay.contains(1));
    CHECK_THROWS_AS(no_decay.set_counter(0, -0.5), nmesh::ParameterError);
    CHECK(no_decay.counter(0) == 2.0);
}
