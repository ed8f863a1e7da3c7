// nmesh/render.cpp — the software rasteriser: framing, visibility, shading, downsampling.
#include "nmesh/render.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "nmesh/error.h"
#include "nmesh/util/math_constants.h"

namespace nmesh {
namespace {

// Largest image side: far beyond any preview, and it keeps fixed-point sample coordinates
// (16384 * 4 samples * 2^kSubpixelBits) and their products well inside 64 bits.
constexpr int kMaxSide = 16384;
constexpr int kMaxSupersample = 4;
// Vertex positions are snapped to 1/256 of a sample, so that coverage is decided exactly in
// integers: two triangles sharing an edge never both cover a sample nor leave a gap between them.
constexpr int kSubpixelBits = 8;
constexpr std::int64_t kSubpixel = std::int64_t(1) << kSubpixelBits;
constexpr std::uint32_t kNoTriangle = std::numeric_limits<std::uint32_t>::max();
// Shading: intensity = kAmbient + kDiffuse * max(0, n . light). The ambient term keeps faces
// turned from the light readable; the two sum to 1 so a face facing the light shows `color` itself.
constexpr double kAmbient = 0.3;
constexpr double kDiffuse = 0.7;
// Direction towards the light in camera coordinates (right, up, towards the viewer): from the
// upper left and in front, so that faces towards the viewer are well lit and relief reads as in
// most illustrations.
constexpr double kLightRight = -1.0, kLightUp = 1.0, kLightToward = 2.0;
// Wireframe lines: at an edge the shaded colour is darkened to kEdgeShade of itself, fading
// linearly to no change one output pixel away on each side — a line about one pixel wide that
// keeps the shading (and the ramp colour) visible on meshes whose edges crowd together.
constexpr double kEdgeShade = 0.2;
// With vertex values, back faces keep the ramp's colour (so the scale still reads on both sides)
// and are darkened to this share of their shaded brightness instead of taking back_color.
constexpr double kBackValueShade = 0.6;
// Back faces are written into the depth buffer this share of the bounding sphere's radius farther
// than they are (over 500 times float's resolution there, and far below a pixel): where a back
// face meets a front one at a silhouette, or lies on it, the two depths tie or differ by rounding
// only, and the front face must win whatever the triangle order, or a closed mesh would show
// specks of the back colour along its outline.
constexpr double kBackDepthShift = 1.0 / 16384;

void check_options(const IndexedMesh& mesh, const RenderOptions& o) {
    if (o.width < 1 || o.width > kMaxSide || o.height < 1 || o.height > kMaxSide)
        throw ParameterError(o.width < 1 || o.width > kMaxSide ? "width" : "height",
                             "render: width and height must be in [1, " + std::to_string(kMaxSide) + "], got " +
                             std::to_string(o.width) + "x" + std::to_string(o.height));
    if (o.supersample < 1 || o.supersample > kMaxSupersample)
        throw ParameterError("supersample", "render: supersample must be in [1, " + std::to_string(kMaxSupersample) + "], got " +
                             std::to_string(o.supersample));
    if (!std::isfinite(o.view.azimuth_deg) || !std::isfinite(o.view.elevation_deg) ||
        std::fabs(o.view.elevation_deg) > 90.0)
        throw ParameterError(std::isfinite(o.view.azimuth_deg) ? "view.elevation_deg" : "view.azimuth_deg",
                             "render: the azimuth must be finite and the elevation in [-90, 90] degrees");
    if (o.vertex_values) {
        const std::vector<float>& values = *o.vertex_values;
        if (values.size() != mesh.positions.size())
            throw ParameterError("vertex_values", "render: vertex_values has " + std::to_string(values.size()) + " values for " +
                                 std::to_string(mesh.positions.size()) + " vertices");
        for (std::size_t i = 0; i < values.size(); ++i)
            if (!std::isfinite(values[i]))
                throw ParameterError("vertex_values", "render: vertex_values[" + std::to_string(i) + "] is not finite");
    }
    const auto finite_or_empty = [](const std::optional<float>& v) { return !v || std::isfinite(*v); };
    if (!finite_or_empty(o.value_min) || !finite_or_empty(o.value_max) ||
        (o.value_min && o.value_max && *o.value_min > *o.value_max))
        throw ParameterError(finite_or_empty(o.value_min) && finite_or_empty(o.value_max) ? "value_min"
                             : finite_or_empty(o.value_min)                             ? "value_max"
                                                                                        : "value_min",
                             "render: value_min and value_max must be finite, with value_min <= value_max");
}

// Marks the vertices that triangles use; checks indices and coordinates.
std::vector<char> used_vertices(const IndexedMesh& mesh) {
    if (mesh.triangles.size() >= kNoTriangle)
        throw InputError("render: more than " + std::to_string(kNoTriangle - 1) + " triangles");
    std::vector<char> used(mesh.positions.size(), 0);
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        for (const std::uint32_t v : mesh.triangles[t]) {
            if (v >= mesh.positions.size())
                throw InputError("render: triangle " + std::to_string(t) + " refers to vertex " + std::to_string(v) +
                                 ", but the mesh has " + std::to_string(mesh.positions.size()) + " vertices");
            if (!used[v] && !is_finite(mesh.positions[v]))
                throw InputError("render: vertex " + std::to_string(v) + " has a non-finite coordinate");
            used[v] = 1;
        }
    }
    return used;
}

Camera make_camera(const IndexedMesh& mesh, const std::vector<char>& used, const RenderOptions& o) {
    Camera cam;
    cam.width = o.width;
    cam.height = o.height;
    const double az = o.view.azimuth_deg * kPi / 180.0, el = o.view.elevation_deg * kPi / 180.0;
    cam.toward = {float(std::cos(el) * std::sin(az)), float(std::sin(el)), float(std::cos(el) * std::cos(az))};
    cam.right = {float(std::cos(az)), 0.0f, float(-std::sin(az))};
    cam.up = cross(cam.toward, cam.right);

    // Bounding sphere: centred on the bounding box of the used vertices, through the farthest one.
    double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    bool any = false;
    for (std::size_t v = 0; v < used.size(); ++v) {
        if (!used[v]) continue;
        for (int k = 0; k < 3; ++k) {
            const double c = mesh.positions[v][k];
            lo[k] = any ? std::min(lo[k], c) : c;
            hi[k] = any ? std::max(hi[k], c) : c;
        }
        any = true;
    }
    const double center[3] = {(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2};
    cam.center = {float(center[0]), float(center[1]), float(center[2])};
    double radius2 = 0.0;
    for (std::size_t v = 0; v < used.size(); ++v) {
        if (!used[v]) continue;
        double d2 = 0.0;
        for (int k = 0; k < 3; ++k) d2 += (mesh.positions[v][k] - center[k]) * (mesh.positions[v][k] - center[k]);
        radius2 = std::max(radius2, d2);
    }
    const double radius = std::sqrt(radius2);
    const double usable = (1.0 - 2.0 * kRenderMargin) * std::min(o.width, o.height);
    cam.scale = radius > 0.0 && std::isfinite(usable / (2.0 * radius)) ? usable / (2.0 * radius) : 1.0;
    return cam;
}

// A vertex in sample space: x right, y down (double), z towards the viewer, and x, y snapped to
// the fixed-point grid.
struct Projected {
    double x, y, z;
    std::int64_t fx, fy;
};

std::vector<Projected> project_vertices(const IndexedMesh& mesh, const std::vector<char>& used, const Camera& cam,
                                        int ss) {
    std::vector<Projected> out(mesh.positions.size(), Projected{0, 0, 0, 0, 0});
    const double s = cam.scale * ss;
    const double cx = 0.5 * cam.width * ss, cy = 0.5 * cam.height * ss;
    for (std::size_t v = 0; v < out.size(); ++v) {
        if (!used[v]) continue;
        const Vec3& p = mesh.positions[v];
        const double d[3] = {double(p.x) - cam.center.x, double(p.y) - cam.center.y, double(p.z) - cam.center.z};
        const auto along = [&](const Vec3& axis) { return d[0] * axis.x + d[1] * axis.y + d[2] * axis.z; };
        Projected& q = out[v];
        q.x = cx + s * along(cam.right);
        q.y = cy - s * along(cam.up);
        q.z = along(cam.toward);
        q.fx = std::llround(q.x * double(kSubpixel));
        q.fy = std::llround(q.y * double(kSubpixel));
    }
    return out;
}

// The nearest triangle at every sample, and its depth.
struct DepthBuffer {
    int width = 0, height = 0;
    std::vector<float> depth;
    std::vector<std::uint32_t> id;
};

// Smallest integer i with i * kSubpixel + kSubpixel / 2 >= f: the first sample centre at or after f.
std::int64_t first_sample_at_or_after(std::int64_t f) {
    const std::int64_t n = f - kSubpixel / 2;
    return n >= 0 ? (n + kSubpixel - 1) / kSubpixel : -((-n) / kSubpixel);
}
// Largest integer i with i * kSubpixel + kSubpixel / 2 <= f.
std::int64_t last_sample_at_or_before(std::int64_t f) {
    const std::int64_t n = f - kSubpixel / 2;
    return n >= 0 ? n / kSubpixel : -((-n + kSubpixel - 1) / kSubpixel);
}

// Writes triangle t into the buffer where it is nearer than what is there. Coverage: the sample
// centres inside the snapped triangle; a centre exactly on an edge belongs to the triangle for
// which that edge, walked with the triangle positively oriented, points down (or left, when
// horizontal) — exactly one of the two triangles sharing the edge.
// Returns whether the triangle is a back face: whether its counter-clockwise normal points away
// from the camera, decided on the snapped vertices (clockwise on the image) so that it agrees
// with the coverage even for a sliver seen edge on, which snapping may turn over. Back faces are
// written back_shift deeper than they are (kBackDepthShift).
bool rasterize(std::uint32_t t, const Projected& a, const Projected& b, const Projected& c, double back_shift,
               DepthBuffer& buf) {
    const Projected* v[3] = {&a, &b, &c};
    std::int64_t area = (v[1]->fx - v[0]->fx) * (v[2]->fy - v[0]->fy) - (v[1]->fy - v[0]->fy) * (v[2]->fx - v[0]->fx);
    if (area == 0) return false;
    // y grows downwards: a triangle counter-clockwise from the camera has a negative area here.
    const bool back = area > 0;
    const double shift = back ? back_shift : 0.0;
    if (area < 0) {
        std::swap(v[1], v[2]);
        area = -area;
    }
    const std::int64_t min_x = std::min({v[0]->fx, v[1]->fx, v[2]->fx}),
                       max_x = std::max({v[0]->fx, v[1]->fx, v[2]->fx});
    const std::int64_t min_y = std::min({v[0]->fy, v[1]->fy, v[2]->fy}),
                       max_y = std::max({v[0]->fy, v[1]->fy, v[2]->fy});
    const std::int64_t i0 = std::max<std::int64_t>(0, first_sample_at_or_after(min_x));
    const std::int64_t i1 = std::min<std::int64_t>(buf.width - 1, last_sample_at_or_before(max_x));
    const std::int64_t j0 = std::max<std::int64_t>(0, first_sample_at_or_after(min_y));
    const std::int64_t j1 = std::min<std::int64_t>(buf.height - 1, last_sample_at_or_before(max_y));
    if (i0 > i1 || j0 > j1) return back;

    // Edge k runs from vertex k+1 to vertex k+2; its function, positive inside, is the weight of
    // vertex k times twice the area.
    std::int64_t step_x[3], step_y[3], row[3], bias[3];
    const std::int64_t px0 = i0 * kSubpixel + kSubpixel / 2, py0 = j0 * kSubpixel + kSubpixel / 2;
    for (int k = 0; k < 3; ++k) {
        const Projected& from = *v[(k + 1) % 3];
        const Projected& to = *v[(k + 2) % 3];
        const std::int64_t dx = to.fx - from.fx, dy = to.fy - from.fy;
        step_x[k] = -dy * kSubpixel;
        step_y[k] = dx * kSubpixel;
        row[k] = dx * (py0 - from.fy) - dy * (px0 - from.fx);
        bias[k] = (dy > 0 || (dy == 0 && dx < 0)) ? 0 : -1;
    }
    const double inv_area = 1.0 / double(area);
    const double z0 = v[0]->z * inv_area, z1 = v[1]->z * inv_area, z2 = v[2]->z * inv_area;
    for (std::int64_t j = j0; j <= j1; ++j) {
        std::int64_t w0 = row[0], w1 = row[1], w2 = row[2];
        std::size_t at = std::size_t(j) * std::size_t(buf.width) + std::size_t(i0);
        for (std::int64_t i = i0; i <= i1; ++i, ++at) {
            if (((w0 + bias[0]) | (w1 + bias[1]) | (w2 + bias[2])) >= 0) {
                const float z = float(double(w0) * z0 + double(w1) * z1 + double(w2) * z2 - shift);
                if (z > buf.depth[at]) {
                    buf.depth[at] = z;
                    buf.id[at] = t;
                }
            }
            w0 += step_x[0];
            w1 += step_x[1];
            w2 += step_x[2];
        }
        for (int k = 0; k < 3; ++k) row[k] += step_y[k];
    }
    return back;
}

// What shading a sample of a triangle needs: its barycentric coordinates as linear functions of
// the sample position, its normal turned towards the viewer, and its heights in output pixels.
struct TriangleShading {
    double b0[3], b1[3];  // b_k(x, y) = c[0] * x + c[1] * y + c[2]; b2 = 1 - b0 - b1
    Vec3 normal;          // unit face normal, facing the viewer
    bool back = false;    // whether the triangle faces away: its vertex normals get flipped, and
                          // it takes back_color (or, with vertex values, is darkened)
    double height[3];     // distance from vertex k to the opposite edge, in output pixels
};

// The unit normal of triangle t, by the counter-clockwise rule (zero when too small for float).
Vec3 face_normal(const IndexedMesh& mesh, std::size_t t) {
    const auto& tri = mesh.triangles[t];
    const Vec3 a = mesh.positions[tri[0]], b = mesh.positions[tri[1]], c = mesh.positions[tri[2]];
    return normalized(cross(b - a, c - a));
}

TriangleShading prepare(const IndexedMesh& mesh, std::size_t t, const std::vector<Projected>& proj, const Camera& cam,
                        int ss, bool back) {
    const auto& tri = mesh.triangles[t];
    const Projected& p0 = proj[tri[0]];
    const Projected& p1 = proj[tri[1]];
    const Projected& p2 = proj[tri[2]];
    TriangleShading s{};
    const double area = (p1.x - p0.x) * (p2.y - p0.y) - (p1.y - p0.y) * (p2.x - p0.x);
    if (area == 0.0) return s;  // covers no sample
    // b0 is the signed area of (p1, p2, sample) over the whole; b1 that of (p2, p0, sample).
    s.b0[0] = -(p2.y - p1.y) / area;
    s.b0[1] = (p2.x - p1.x) / area;
    s.b0[2] = -(s.b0[0] * p1.x + s.b0[1] * p1.y);
    s.b1[0] = -(p0.y - p2.y) / area;
    s.b1[1] = (p0.x - p2.x) / area;
    s.b1[2] = -(s.b1[0] * p2.x + s.b1[1] * p2.y);
    const Projected* pv[3] = {&p0, &p1, &p2};
    for (int k = 0; k < 3; ++k) {
        const Projected& a = *pv[(k + 1) % 3];
        const Projected& b = *pv[(k + 2) % 3];
        const double len = std::hypot(b.x - a.x, b.y - a.y);
        s.height[k] = std::fabs(area) / len / ss;
    }
    const Vec3 n = face_normal(mesh, t);
    s.back = back;
    s.normal = s.back ? -n : n;
    if (squared_norm(s.normal) == 0.0f) s.normal = cam.toward;  // too small for float: face the viewer
    return s;
}

std::vector<Vec3> vertex_normals(const IndexedMesh& mesh) {
    std::vector<Vec3> normals(mesh.positions.size());
    for (const auto& tri : mesh.triangles) {
        const Vec3 a = mesh.positions[tri[0]], b = mesh.positions[tri[1]], c = mesh.positions[tri[2]];
        const Vec3 n = cross(b - a, c - a);  // length: twice the area, hence area weighting
        for (const std::uint32_t v : tri) normals[v] += n;
    }
    for (Vec3& n : normals) n = normalized(n);
    return normals;
}

// The vertex values mapped to [0, 1] as RenderOptions describes.
std::vector<float> ramp_positions(const RenderOptions& o, const std::vector<char>& used) {
    const std::vector<float>& values = *o.vertex_values;
    float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
    for (std::size_t v = 0; v < values.size(); ++v) {
        if (!used[v]) continue;
        lo = std::min(lo, values[v]);
        hi = std::max(hi, values[v]);
    }
    if (o.value_min) lo = *o.value_min;
    if (o.value_max) hi = *o.value_max;
    std::vector<float> t(values.size(), 0.0f);
    for (std::size_t v = 0; v < values.size(); ++v) {
        if (hi > lo)
            t[v] = std::clamp(float((double(values[v]) - lo) / (double(hi) - lo)), 0.0f, 1.0f);
        else
            t[v] = values[v] > hi ? 1.0f : 0.0f;
    }
    return t;
}

}  // namespace

Vec3 Camera::project(const Vec3& p) const {
    const Vec3 d = p - center;
    return {float(0.5 * width + scale * dot(d, right)), float(0.5 * height - scale * dot(d, up)), dot(d, toward)};
}

Camera frame_camera(const IndexedMesh& mesh, const RenderOptions& options) {
    check_options(mesh, options);
    return make_camera(mesh, used_vertices(mesh), options);
}

std::array<std::uint8_t, 3> ramp_color(double t) {
    static constexpr double kStops[5][3] = {
        {40, 80, 220},   // blue
        {40, 190, 220},  // cyan
        {60, 190, 70},   // green
        {240, 210, 40},  // yellow
        {220, 40, 30},   // red
    };
    t = std::isnan(t) ? 0.0 : std::clamp(t, 0.0, 1.0) * 4.0;
    const int k = std::min(3, int(t));
    const double f = t - k;
    std::array<std::uint8_t, 3> c{};
    for (int i = 0; i < 3; ++i) c[i] = std::uint8_t(std::lround(kStops[k][i] + f * (kStops[k + 1][i] - kStops[k][i])));
    return c;
}

Image render(const IndexedMesh& mesh, const RenderOptions& options) {
    check_options(mesh, options);
    const std::vector<char> used = used_vertices(mesh);
    const Camera cam = make_camera(mesh, used, options);
    const int ss = options.supersample;

    // Visibility: every triangle into the depth buffer.
    DepthBuffer buf;
    buf.width = options.width * ss;
    buf.height = options.height * ss;
    const std::size_t samples = std::size_t(buf.width) * std::size_t(buf.height);
    buf.depth.assign(samples, -std::numeric_limits<float>::infinity());
    buf.id.assign(samples, kNoTriangle);
    const std::vector<Projected> proj = project_vertices(mesh, used, cam, ss);
    std::vector<char> back(mesh.triangles.size(), 0);
    // The bounding sphere's radius, as make_camera fitted it into the image.
    const double radius = 0.5 * (1.0 - 2.0 * kRenderMargin) * std::min(options.width, options.height) / cam.scale;
    const double back_shift = kBackDepthShift * radius;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const auto& tri = mesh.triangles[t];
        back[t] = rasterize(std::uint32_t(t), proj[tri[0]], proj[tri[1]], proj[tri[2]], back_shift, buf);
    }

    // Shading: per-triangle set-up for the visible triangles only.
    std::vector<TriangleShading> shading(mesh.triangles.size());
    std::vector<char> prepared(mesh.triangles.size(), 0);
    for (const std::uint32_t t : buf.id) {
        if (t == kNoTriangle || prepared[t]) continue;
        shading[t] = prepare(mesh, t, proj, cam, ss, back[t]);
        prepared[t] = 1;
    }
    const std::vector<Vec3> normals = options.smooth ? vertex_normals(mesh) : std::vector<Vec3>();
    const std::vector<float> ramp = options.vertex_values ? ramp_positions(options, used) : std::vector<float>();
    const Vec3 light =
        normalized(cam.right * float(kLightRight) + cam.up * float(kLightUp) + cam.toward * float(kLightToward));

    const auto shade = [&](std::uint32_t t, double x, double y, float out[3]) {
        const TriangleShading& s = shading[t];
        const auto& tri = mesh.triangles[t];
        const double b0 = s.b0[0] * x + s.b0[1] * y + s.b0[2];
        const double b1 = s.b1[0] * x + s.b1[1] * y + s.b1[2];
        const double b2 = 1.0 - b0 - b1;
        Vec3 n = s.normal;
        if (options.smooth) {
            const Vec3 m = normals[tri[0]] * float(b0) + normals[tri[1]] * float(b1) + normals[tri[2]] * float(b2);
            const Vec3 u = normalized(s.back ? -m : m);
            if (squared_norm(u) > 0.0f) n = u;
        }
        double intensity = kAmbient + kDiffuse * std::max(0.0f, dot(n, light));
        const std::array<std::uint8_t, 3>& surface = s.back ? options.back_color : options.color;
        float base[3] = {float(surface[0]), float(surface[1]), float(surface[2])};
        if (!ramp.empty()) {
            const auto c = ramp_color(b0 * ramp[tri[0]] + b1 * ramp[tri[1]] + b2 * ramp[tri[2]]);
            for (int i = 0; i < 3; ++i) base[i] = c[i];
            if (s.back) intensity *= kBackValueShade;
        }
        for (int i = 0; i < 3; ++i) out[i] = float(base[i] * intensity);
        if (options.wireframe) {
            const double d = std::min(
                {std::max(0.0, b0) * s.height[0], std::max(0.0, b1) * s.height[1], std::max(0.0, b2) * s.height[2]});
            const float keep = float(1.0 - (1.0 - kEdgeShade) * std::clamp(1.0 - d, 0.0, 1.0));
            for (int i = 0; i < 3; ++i) out[i] *= keep;
        }
    };

    // Each pixel: the mean of its samples.
    Image image;
    image.width = options.width;
    image.height = options.height;
    image.rgb.resize(3 * std::size_t(options.width) * std::size_t(options.height));
    const float inv_samples = 1.0f / float(ss * ss);
    for (int y = 0; y < options.height; ++y) {
        for (int x = 0; x < options.width; ++x) {
            float sum[3] = {0, 0, 0};
            for (int sy = 0; sy < ss; ++sy) {
                const int row = y * ss + sy;
                for (int sx = 0; sx < ss; ++sx) {
                    const int col = x * ss + sx;
                    const std::uint32_t t = buf.id[std::size_t(row) * std::size_t(buf.width) + std::size_t(col)];
                    float c[3] = {float(options.background[0]), float(options.background[1]),
                                  float(options.background[2])};
                    if (t != kNoTriangle) shade(t, col + 0.5, row + 0.5, c);
                    for (int i = 0; i < 3; ++i) sum[i] += c[i];
                }
            }
            std::uint8_t* px = &image.rgb[3 * (std::size_t(y) * std::size_t(options.width) + std::size_t(x))];
            for (int i = 0; i < 3; ++i) px[i] = std::uint8_t(std::clamp(sum[i] * inv_samples + 0.5f, 0.0f, 255.0f));
        }
    }
    return image;
}

}  // namespace nmesh
