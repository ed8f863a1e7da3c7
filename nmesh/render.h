// nmesh/render.h — a headless software rasteriser: a triangle mesh to an RGB image, no GPU.
//
// Meant for looking at reconstructions (previews, figures, error maps), not for speed records:
//   - orthographic camera framing the mesh's bounding sphere (centred on its bounding box, through
//     its farthest vertex), so every view of a mesh has the same scale and nothing is cut off;
//   - z-buffer visibility: the nearest triangle at each sample whatever the triangle order (only
//     between overlapping coplanar triangles facing the same way does the first one win; a back
//     face loses to a front face it lies on or meets, as along a closed mesh's outline);
//   - Lambert + ambient shading under one directional light from the camera's upper left, the
//     light fixed to the camera; back faces (whose counter-clockwise normal points away from the
//     camera) are lit like front faces, the normal turned towards the viewer, but drawn in their
//     own colour: the far side of an open surface, the inside seen through a hole and flipped
//     triangles stand out instead of vanishing or passing for front faces. A closed,
//     outward-facing mesh shows no back face from outside, so its image does not depend on the
//     back colour;
//   - smooth (interpolated per-vertex normals) or flat (one normal per triangle) shading, an
//     optional wireframe, and optional per-vertex values shown through a colour ramp;
//   - supersampling for anti-aliased edges.
//
// Coordinates: y is up. The front view looks along -z (the camera on the +z side), as the Stanford
// scans and most modelling tools are laid out.
//
// Cost: one pass over the triangles into a depth buffer of triangle ids (a fixed-point, watertight
// edge-function rasteriser), then one shading pass per sample. Memory: 8 bytes per sample
// (width * height * supersample^2), 3 bytes per pixel, about 100 bytes per triangle and 50 per
// vertex. Measured (one core, Release build) at
// 1024x1024 on the 69,451-triangle Stanford bunny and on a 59,996-triangle reconstruction of it:
// about 45 ms with supersample 1 and 90-100 ms with the default 2, wireframe or not.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "nmesh/indexed_mesh.h"
#include "nmesh/vec3.h"

namespace nmesh {

// Where the camera looks from: two angles, in degrees.
struct View {
    // Around the vertical (y) axis: 0 looks from the front (+z side), 90 from the right (+x side),
    // 180 from the back, 270 from the left.
    double azimuth_deg = 0.0;
    // Above the horizontal plane, in [-90, 90]: 90 looks straight down, with +z at the image's
    // bottom; -90 looks straight up.
    double elevation_deg = 0.0;

    static View front() { return {0.0, 0.0}; }
    static View side() { return {90.0, 0.0}; }
    static View top() { return {0.0, 90.0}; }
    // The isometric view: the cube's diagonal (1, 1, 1) points at the camera, so the three visible
    // faces of an axis-aligned cube look alike (elevation atan(1 / sqrt 2) = 35.26 degrees).
    static View iso() { return {45.0, 35.264389682754654}; }
};

struct RenderOptions {
    // Image size in pixels, each in [1, 16384].
    int width = 1024;
    int height = 1024;
    View view = View::front();
    // true: per-vertex normals (the area-weighted mean of the incident triangles' normals)
    // interpolated across each triangle, for a smooth surface. false: each triangle's own normal,
    // so the facets show.
    bool smooth = true;
    // Draws every visible edge over the shading: at an edge the shaded colour is darkened to 20%
    // of itself, fading linearly to no change one pixel away (distances in output pixels), so the
    // shading still shows where edges crowd together. Edges hidden by the surface stay hidden;
    // silhouette edges, drawn from one side only, come out half as wide.
    bool wireframe = false;
    std::array<std::uint8_t, 3> background{255, 255, 255};
    // The surface's colour, before shading (a light grey-blue that reads well under the light).
    std::array<std::uint8_t, 3> color{190, 200, 220};
    // The colour of back faces, before shading: a warm tan (E0B090) that tells the back of a sheet
    // from the cool front at a glance, under the light and in shadow, and against a white
    // background. With vertex_values it is not used: back faces keep the ramp's colour and are
    // darkened to 60% of their shaded brightness.
    std::array<std::uint8_t, 3> back_color{224, 176, 144};
    // Optional: one value per mesh position (e.g. its distance to the point cloud), interpolated
    // across the triangles and shown through ramp_color() in place of `color` and `back_color`,
    // still shaded (back faces darkened, see back_color).
    // Values are mapped linearly from [value_min, value_max] to [0, 1] and clamped; a bound left
    // empty is the smallest / largest value over the vertices that triangles use. When the range
    // is a single value, values above it map to 1 and the others to 0.
    const std::vector<float>* vertex_values = nullptr;
    std::optional<float> value_min;
    std::optional<float> value_max;
    // Samples per pixel along each axis, in [1, 4]: each pixel is the mean of supersample^2
    // samples, which smooths silhouettes and edges; cost and memory grow with its square.
    int supersample = 2;
};

// An RGB image: 3 bytes (red, green, blue) per pixel, rows from top to bottom, each from left to
// right — the layout write_png takes.
struct Image {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgb;

    std::array<std::uint8_t, 3> pixel(int x, int y) const {
        const std::size_t i = 3 * (std::size_t(y) * std::size_t(width) + std::size_t(x));
        return {rgb[i], rgb[i + 1], rgb[i + 2]};
    }
};

// The orthographic camera of a render, in output pixels.
struct Camera {
    Vec3 center;         // centre of the bounding sphere; it lands on the centre of the image
    Vec3 right;          // unit vector along the image's x axis
    Vec3 up;             // unit vector towards the image's top
    Vec3 toward;         // unit vector from the scene towards the camera
    double scale = 1.0;  // pixels per mesh unit
    int width = 0;
    int height = 0;

    // Where p lands: x to the right and y down, in pixels from the image's top-left corner (pixel
    // (i, j) covers [i, i + 1) x [j, j + 1), its centre at (i + 0.5, j + 0.5)); z is the depth
    // towards the camera in mesh units, relative to the centre (larger is nearer).
    Vec3 project(const Vec3& p) const;
};

// Share of the image's shorter side left free on each side of the bounding sphere: the sphere's
// diameter spans 90% of min(width, height).
constexpr double kRenderMargin = 0.05;

// The camera render() uses: the view's direction, and a scale that fits the bounding sphere of the
// vertices used by triangles into the image with kRenderMargin on each side. A mesh without
// triangles, or whose triangles all sit on one point, gets scale 1.
// Throws ParameterError for options out of range (see render) and InputError for a triangle that
// refers to a missing vertex or a used vertex with a non-finite coordinate.
Camera frame_camera(const IndexedMesh& mesh, const RenderOptions& options);

// Renders the mesh. Triangles may come in any order and orientation; degenerate triangles and
// unused vertices are ignored; a mesh without triangles gives an image of the background colour.
// Throws ParameterError if width or height is outside [1, 16384], supersample outside [1, 4],
// the view's angles are not finite or the elevation is outside [-90, 90], vertex_values is given
// but not one finite value per position, or value_min > value_max; InputError as frame_camera.
// Cost: O(triangles + covered samples + pixels); see the top of this file.
Image render(const IndexedMesh& mesh, const RenderOptions& options = {});

// The colour ramp of vertex values, t in [0, 1] (clamped): blue (0), cyan (0.25), green (0.5),
// yellow (0.75), red (1), linear in between — cold for small errors, hot for large ones.
std::array<std::uint8_t, 3> ramp_color(double t);

}  // namespace nmesh
