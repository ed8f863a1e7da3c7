// nmesh/cli/render_command.cpp — `nmesh render`: options, the optional error map, the PNG.
#include "nmesh/cli/render_command.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "nmesh/bounding_box.h"
#include "nmesh/cli/arguments.h"
#include "nmesh/error.h"
#include "nmesh/io.h"
#include "nmesh/metrics.h"
#include "nmesh/render/png_writer.h"
#include "nmesh/spatial/point_grid.h"
#include "nmesh/render.h"

namespace nmesh::cli {
namespace {

constexpr const char* kRenderUsage =
    "usage: nmesh render MESH -o IMAGE.png [options]\n"
    "\n"
    "Draws MESH (.ply, .obj, .off) to a PNG image with a software renderer (no GPU needed): an\n"
    "orthographic view framing the whole mesh, lit from the upper left. y is up; the front view\n"
    "looks along -z.\n"
    "\n"
    "options:\n"
    "  -o, --output FILE      the PNG image to write (required)\n"
    "  --size WxH             image size in pixels, each 1 to 16384 (default 1024x1024; N: NxN)\n"
    "  --view NAME            front (from +z), side (from +x), top (from +y) or iso (default front)\n"
    "  --azimuth A            camera angle around the vertical axis, degrees (0 front, 90 side)\n"
    "  --elevation E          camera angle above the horizon, degrees, -90 to 90 (90 top)\n"
    "  --flat                 flat shading: one normal per triangle, so the facets show\n"
    "  --wireframe            draw the triangles' edges over the shading\n"
    "  --color RRGGBB         surface colour, hexadecimal (default BEC8DC)\n"
    "  --back-color RRGGBB    colour of back faces, those turned away from the camera (the far\n"
    "                         side of an open surface, flipped triangles), hexadecimal (default\n"
    "                         E0B090); with --error-map they keep the map's colours instead,\n"
    "                         darkened to 60%\n"
    "  --background RRGGBB    background colour, hexadecimal (default FFFFFF)\n"
    "  --supersample N        N x N samples per pixel for smooth edges, 1 to 4 (default 2)\n"
    "  --error-map POINTS     colour each vertex by its distance to the nearest point of the cloud\n"
    "                         POINTS: blue (0), cyan, green, yellow, red (the largest distance);\n"
    "                         the scale is printed to stderr\n"
    "  --error-max D          with --error-map: distance shown red (default the largest), so\n"
    "                         that several images share one scale\n";

bool wants_help(int argc, char** argv) {
    for (int i = 2; i < argc; ++i)
        if (!std::strcmp(argv[i], "--help") || !std::strcmp(argv[i], "-h")) return true;
    return false;
}

bool ends_with_png(const std::string& path) {
    if (path.size() < 4) return false;
    std::string ext = path.substr(path.size() - 4);
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    return ext == ".png";
}

// One side of --size, in [1, 16384].
int parse_side(const std::string& s, const std::string& whole) {
    int v = 0;
    const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (s.empty() || ec != std::errc() || ptr != s.data() + s.size() || v < 1 || v > 16384)
        throw UsageError("option --size needs WxH or N, each from 1 to 16384, got '" + whole + "'");
    return v;
}

// "RRGGBB" or "#RRGGBB", hexadecimal.
std::array<std::uint8_t, 3> parse_color(const std::string& name, const std::string& text) {
    const std::string s = !text.empty() && text[0] == '#' ? text.substr(1) : text;
    std::uint32_t v = 0;
    const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v, 16);
    if (s.size() != 6 || ec != std::errc() || ptr != s.data() + s.size())
        throw UsageError("option " + name + " needs a colour RRGGBB in hexadecimal, got '" + text + "'");
    return {std::uint8_t(v >> 16), std::uint8_t(v >> 8), std::uint8_t(v)};
}

View parse_view(const Arguments& args) {
    const bool angles = args.has("--azimuth") || args.has("--elevation");
    if (args.has("--view") && angles) throw UsageError("give either --view or --azimuth/--elevation, not both");
    if (angles) {
        View v{args.number("--azimuth", 0.0), args.number("--elevation", 0.0)};
        if (v.elevation_deg < -90.0 || v.elevation_deg > 90.0)
            throw UsageError("option --elevation must be from -90 to 90 degrees");
        return v;
    }
    const std::string name = args.text("--view", "front");
    if (name == "front") return View::front();
    if (name == "side") return View::side();
    if (name == "top") return View::top();
    if (name == "iso") return View::iso();
    throw UsageError("option --view needs front, side, top or iso, got '" + name + "'");
}

// Distances from the mesh's vertices to the cloud, with the colour scale printed to stderr.
// `error_max` is the distance shown red, or 0 for the largest one.
std::vector<float> error_map(const std::string& points_path, const IndexedMesh& mesh, double error_max,
                             RenderOptions& options) {
    const PointCloud cloud = read_points(points_path);
    if (cloud.empty()) throw IoError(points_path, "no points");
    std::vector<float> distances = vertex_distances_to_cloud(cloud.points, mesh);
    double largest = 0.0, sum = 0.0;
    for (const float d : distances) {
        largest = std::max(largest, double(d));
        sum += d;
    }
    const double mean = distances.empty() ? 0.0 : sum / double(distances.size());
    const double top = error_max > 0.0 ? error_max : largest;
    options.value_min = 0.0f;
    options.value_max = float(top);
    const double diagonal = cloud.bounds().diagonal();
    const auto share = [&](double d) { return diagonal > 0.0 ? 100.0 * d / diagonal : 0.0; };
    std::fprintf(
        stderr,
        "nmesh: error map: distance from each vertex to the nearest point of %s\n"
        "nmesh:   blue 0 | cyan %.4g | green %.4g | yellow %.4g | red %s%.4g (%.3g%% of the cloud's diagonal)\n"
        "nmesh:   largest %.4g (%.3g%%), mean %.4g (%.3g%%)\n",
        points_path.c_str(), top / 4, top / 2, 3 * top / 4, top < largest ? ">= " : "", top, share(top), largest,
        share(largest), mean, share(mean));
    return distances;
}

}  // namespace

int run_render(int argc, char** argv) {
    if (wants_help(argc, argv)) {
        std::fputs(kRenderUsage, stdout);
        return 0;
    }
    const Arguments args(argc, argv, 2, {"--flat", "--wireframe"},
                         {"-o", "--output", "--size", "--view", "--azimuth", "--elevation", "--color", "--back-color",
                          "--background", "--supersample", "--error-map", "--error-max"});
    if (args.positional().size() != 1) throw UsageError("render takes one MESH file");
    const std::string input = args.positional()[0];
    const std::string output = args.has("-o") ? args.text("-o") : args.text("--output");
    if (output.empty()) throw UsageError("render needs an output image: -o IMAGE.png");
    if (!ends_with_png(output)) throw UsageError("the output image must be a .png file, got '" + output + "'");
    if (output == input) throw UsageError("the output file must not be the input file");
    if (args.has("--error-max") && !args.has("--error-map"))
        throw UsageError("option --error-max needs --error-map POINTS");
    const double error_max = args.number("--error-max", 0.0);
    if (args.has("--error-max") && !(error_max > 0.0)) throw UsageError("option --error-max must be positive");

    RenderOptions options;
    if (args.has("--size")) {
        const std::string size = args.text("--size");
        const auto x = size.find_first_of("xX");
        options.width = parse_side(size.substr(0, x), size);
        options.height = x == std::string::npos ? options.width : parse_side(size.substr(x + 1), size);
    }
    options.view = parse_view(args);
    options.smooth = !args.has("--flat");
    options.wireframe = args.has("--wireframe");
    if (args.has("--color")) options.color = parse_color("--color", args.text("--color"));
    if (args.has("--back-color")) options.back_color = parse_color("--back-color", args.text("--back-color"));
    if (args.has("--background")) options.background = parse_color("--background", args.text("--background"));
    const std::uint64_t supersample = args.count("--supersample", std::uint64_t(options.supersample));
    if (supersample < 1 || supersample > 4) throw UsageError("option --supersample must be from 1 to 4");
    options.supersample = int(supersample);

    const IndexedMesh mesh = read_mesh(input);
    if (mesh.triangles.empty()) throw IoError(input, "no triangles to draw (is it a point cloud?)");
    std::vector<float> distances;
    if (args.has("--error-map")) {
        distances = error_map(args.text("--error-map"), mesh, error_max, options);
        options.vertex_values = &distances;
    }
    Image image;
    try {
        image = render(mesh, options);
    } catch (const InputError& e) {
        throw IoError(input, e.what());
    }
    write_png(output, image.width, image.height, image.rgb);
    std::fprintf(stderr, "nmesh: wrote %s (%dx%d)\n", output.c_str(), image.width, image.height);
    return 0;
}

}  // namespace nmesh::cli
