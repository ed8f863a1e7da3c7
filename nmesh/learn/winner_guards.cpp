// The guards beyond the paper on the winner of a sample (NeuralMesh, nmesh/learn/neural_mesh.h):
// the fold guard of step 3 (Parameters::fold_guard) and the samples' sides
// (NeuralMesh::set_sample_sides). Both read the winner's ring, which step 4 reads next.
#include <algorithm>

#include "nmesh/learn/neural_mesh.h"
#include "nmesh/util/float4.h"

namespace nmesh {

// Choice beyond the paper (Parameters::fold_guard): where step 3 would move the winner from p to
// q, the position it goes to instead, so that no more of its triangles fold back against its fan.
// With a_i = v_i - p for the clockwise ring v_0 .. v_k-1, triangle i (w, v_i+1, v_i) has the
// outward normal n_i = a_i+1 x a_i, and N = sum of n_i is the vector area of the ring polygon:
// the same wherever w is. Triangle i is folded when f_i = n_i . N <= 0 (w's projection along N
// lies outside the ring polygon's kernel, on the far side of edge i). f_i is linear in w's
// position: at p + d it is f_i + e_i . (N x d), with e_i = v_i+1 - v_i.
//  - A move that would leave more triangles folded than were folded at p is shortened to half of
//    the way to where the first of them folds (not making it at all leaves vertices stranded off
//    the surface).
//  - A winner found folded goes instead half-way to the centroid of its ring, along its tangent
//    plane (eq. 3-5 with a weight of 1/2), when that leaves fewer triangles folded. Choice: 1/2
//    (the whole way leaves the two sheets of a flat cloud's mesh rougher).
// Why: while the mesh is coarse against the shape (the first tens of vertices; a thin leg or ear
// a few hundred vertices on) it is nearly flat there, and a winner moved past the edge of its
// ring folds its fan through the opposite layer. Nothing in steps 4-8 unfolds it, and the folded
// part grows with the mesh, inside out (docs/algorithm.md has the measurements). O(k), on the ring
// positions step 4 reads next; only while the mesh is coarse (kFoldGuardBelow).
Vec3 NeuralMesh::guard_fold(const Vec3& p, const Vec3& q, const std::uint32_t* ring, std::uint32_t k) {
    using namespace float4;  // F4, load, yzx, cross, cross_zxy, dot, dot2, to_vec3
    const Vec3* pos = mesh_.positions().data();
    const F4 p4 = load(p);
    // N, its cross products summed with their lanes rotated (cross_zxy, as in step 4). The a_i
    // are read again below (from the cache) rather than kept.
    const F4 last = load(pos[ring[k - 1]]) - p4;
    F4 rotated = F4{}, prev = last, rprev = yzx(last);
    for (std::uint32_t i = 0; i < k; ++i) {
        const F4 a = load(pos[ring[i]]) - p4, ra = yzx(a);
        rotated = rotated + cross_zxy(a, ra, prev, rprev);  // n_i-1 = a_i x a_i-1
        prev = a;
        rprev = ra;
    }
    const F4 normal = yzx(rotated), rnormal = yzx(normal);
    // f_i-1 = (a_i x a_i-1) . N = a_i . (a_i-1 x N), and the change at q = p + d is
    // e_i-1 . (N x d) = a_i . m - a_i-1 . m, m = N x d: both are dot products with a_i (dot2).
    // `count` gives the number of triangles folded at p and at p + d, and the fraction of d at
    // which the first triangle unfolded at p folds (1 when none does).
    const auto count = [&](const F4& d, std::uint32_t& folded_p, std::uint32_t& folded_d, float& first) {
        const F4 m = cross(normal, d);
        F4 c_prev = yzx(cross_zxy(last, yzx(last), normal, rnormal));  // a_k-1 x N
        float g_prev = dot(last, m);
        folded_p = folded_d = 0;
        first = 1.0f;
        for (std::uint32_t i = 0; i < k; ++i) {
            const F4 a = load(pos[ring[i]]) - p4, ra = yzx(a);
            float f, g;
            dot2(c_prev, m, a, f, g);
            const float f_d = f + (g - g_prev);
            folded_p += f <= 0.0f;
            folded_d += f_d <= 0.0f;
            if (f > 0.0f && f_d <= 0.0f) first = std::min(first, f / (f - f_d));
            c_prev = yzx(cross_zxy(a, ra, normal, rnormal));
            g_prev = g;
        }
    };
    std::uint32_t folded_p, folded_q;
    float first;
    const F4 step = load(q) - p4;
    count(step, folded_p, folded_q, first);
    Vec3 to = q;
    if (folded_q > folded_p) {
        to = to_vec3(p4 + step * (0.5f * first));
        ++stats_.moves_shortened;
    }
    if (folded_p > 0) {
        // A folded winner: half of its Laplacian (eq. 5), without its part along N.
        F4 sum = F4{};
        for (std::uint32_t i = 0; i < k; ++i) sum = sum + (load(pos[ring[i]]) - p4);
        const F4 laplacian = sum * (0.5f / float(k));
        const float nn = dot(normal, normal);
        const F4 d = nn > 0.0f ? laplacian - normal * (dot(laplacian, normal) / nn) : laplacian;
        std::uint32_t unused, folded_c;
        float unused_first;
        count(d, unused, folded_c, unused_first);
        if (folded_c < std::min(folded_p, folded_q)) {
            to = to_vec3(p4 + d);
            ++stats_.folds_undone;
        }
    }
    return to;
}

// Beyond the paper (sample sides, set_sample_sides): whether the winner w's fan faces the side
// `side` a sample was taken from: its vector area N (the sum of the cross products of
// consecutive ring edges, the same wherever w is) against it. A sample without a side (0) is
// faced by every vertex. O(k), on the ring positions step 4 reads next.
bool NeuralMesh::faces_side(Vertex w, const Vec3& side, const std::uint32_t* ring, std::uint32_t k) const {
    if (side.x == 0.0f && side.y == 0.0f && side.z == 0.0f) return true;
    const Vec3* pos = mesh_.positions().data();
    const Vec3 p = pos[w.idx];
    Vec3 normal{}, prev = pos[ring[k - 1]] - p;
    for (std::uint32_t i = 0; i < k; ++i) {
        const Vec3 a = pos[ring[i]] - p;
        normal += cross(a, prev);
        prev = a;
    }
    return dot(normal, side) >= 0.0f;
}

}  // namespace nmesh
