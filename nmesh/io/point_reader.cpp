// nmesh/io/point_reader.cpp — read_points, inspect_file and read_geometry: the format chosen by
// the extension or the first bytes, then the reader of that format (format_readers.h).
#include "nmesh/io.h"

#include "nmesh/error.h"
#include "nmesh/io/format_readers.h"

namespace nmesh {
namespace {

using namespace io_detail;

enum class Format { ply, xyz, pts, obj, off };

std::string lower_extension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

Format choose_format(const std::string& path, InputFile& in) {
    const std::string ext = lower_extension(path);
    if (ext == ".ply") return Format::ply;
    if (ext == ".xyz" || ext == ".txt" || ext == ".csv") return Format::xyz;
    if (ext == ".pts") return Format::pts;
    if (ext == ".obj") return Format::obj;
    if (ext == ".off") return Format::off;
    // Unknown extension: sniff the first bytes.
    constexpr std::size_t kSniffBytes = 16;  // the longest keyword recognised here, with room to spare
    in.fill(kSniffBytes);
    const std::string_view head(reinterpret_cast<const char*>(in.data()), in.available());
    if (head.size() >= 4 && head.substr(0, 3) == "ply" && (head[3] == '\n' || head[3] == '\r')) return Format::ply;
    const std::size_t keyword_end = head.find_first_of(" \t\r\n");
    if (keyword_end != std::string_view::npos && is_off_keyword(head.substr(0, keyword_end))) return Format::off;
    in.fail("unknown file format: " + (ext.empty() ? std::string("no extension") : "extension " + quote_token(ext)) +
            " is not one of .ply .xyz .txt .pts .csv .obj .off, and the content is not PLY or OFF");
}

}  // namespace

FileGeometry read_geometry(const std::string& path, ReadFaces faces) {
    InputFile in(path);
    if (in.size() == 0) in.fail("empty file");
    FileGeometry g;
    switch (choose_format(path, in)) {
        case Format::ply:
            read_ply(in, faces, g);
            break;
        case Format::xyz:
            read_xyz(in, false, g);
            break;
        case Format::pts:
            read_xyz(in, true, g);
            break;
        case Format::obj:
            read_obj(in, faces, g);
            break;
        case Format::off:
            read_off(in, faces, g);
            break;
    }
    if (faces == ReadFaces::yes && g.positions.size() > std::numeric_limits<std::uint32_t>::max())
        in.fail("too many vertices for 32-bit face indices (" + std::to_string(g.positions.size()) + ")");
    return g;
}

namespace io_detail {

std::vector<std::array<std::uint32_t, 3>> fan_triangles(const FileGeometry& g) {
    std::vector<std::array<std::uint32_t, 3>> triangles;
    if (g.face_offsets.empty()) return triangles;
    // Every polygon has >= 3 corners (read_geometry checks), so it gives corners - 2 triangles.
    const std::size_t faces = g.face_offsets.size() - 1;
    triangles.reserve(g.face_indices.size() - 2 * faces);
    for (std::size_t f = 0; f < faces; ++f) {
        const std::uint32_t* c = g.face_indices.data() + g.face_offsets[f];
        const std::size_t corners = g.face_offsets[f + 1] - g.face_offsets[f];
        for (std::size_t i = 1; i + 1 < corners; ++i) triangles.push_back({c[0], c[i], c[i + 1]});
    }
    return triangles;
}

}  // namespace io_detail

PointCloud read_points(const std::string& path, PointReadReport* report) {
    FileGeometry g = read_geometry(path, ReadFaces::no);
    PointCloud cloud;
    cloud.points = std::move(g.positions);
    const auto kept_end =
        std::remove_if(cloud.points.begin(), cloud.points.end(), [](const Vec3& p) { return !is_finite(p); });
    const auto dropped = static_cast<std::uint64_t>(cloud.points.end() - kept_end);
    cloud.points.erase(kept_end, cloud.points.end());
    if (report) {
        report->format = g.format == "ply" ? "ply " + g.encoding : g.format;
        report->points_read = cloud.points.size();
        report->non_finite_dropped = dropped;
    }
    return cloud;
}

FileInfo inspect_file(const std::string& path) {
    FileGeometry g;
    std::string face_error;
    try {
        g = read_geometry(path, ReadFaces::yes);
    } catch (const IoError& e) {
        // Faces that make no mesh, or any other error: read again without the faces, which
        // throws every error read_points would and summarises the rest.
        g = read_geometry(path, ReadFaces::no);
        face_error = e.what();
    }
    FileInfo info;
    info.format = g.format;
    info.encoding = g.encoding;
    std::error_code ec;
    info.file_size = std::filesystem::file_size(path, ec);
    info.elements = std::move(g.elements);
    info.faces = g.face_count;
    for (const Vec3& p : g.positions) {
        if (!is_finite(p)) {
            ++info.non_finite;
            continue;
        }
        ++info.points;
        info.bounds.extend(p);
    }
    if (!face_error.empty()) {
        if (g.face_count > 0) info.topology_error = face_error;
    } else if (!g.face_offsets.empty()) {
        IndexedMesh mesh;
        mesh.triangles = fan_triangles(g);
        mesh.positions = std::move(g.positions);
        info.topology = mesh_topology(mesh);
    }
    return info;
}

}  // namespace nmesh
