// nmesh/mesh_io.cpp — mesh writers (PLY, OBJ, OFF), the atomic file write, and read_mesh.
#include "nmesh/io.h"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string_view>
#include <system_error>

#ifdef _WIN32
#include <process.h>
#else
#include <unistd.h>
#endif

#include "nmesh/error.h"
#include "nmesh/io/format_readers.h"

namespace nmesh {
namespace {

long process_id() {
#ifdef _WIN32
    return static_cast<long>(_getpid());
#else
    return static_cast<long>(::getpid());
#endif
}

// Distinguishes the temporaries of concurrent writes from one process.
std::atomic<unsigned long> temp_counter{0};

enum class MeshFormat { ply, obj, off };
MeshFormat mesh_format(const std::string& path);

// Whether `path` names something that exists and is neither a regular file nor a directory: a
// device such as /dev/null or /dev/stdout, a pipe, a socket.
bool is_special_file(const std::string& path) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);
    return !ec && fs::exists(st) && !fs::is_regular_file(st) && !fs::is_directory(st);
}

// Flushes and closes `out`; an empty string when every write succeeded, else why not.
std::string close_stream(std::ofstream& out) {
    errno = 0;
    out.flush();
    if (out) out.close();
    if (!out.fail()) return {};
    return errno != 0 ? std::strerror(errno) : "the stream reported an error";
}

}  // namespace

void check_output_location(const std::string& path) {
    namespace fs = std::filesystem;
    if (path.empty()) throw IoError("", "cannot write a file without a name");
    if (is_special_file(path)) return;  // written in place: its directory is not written
    const fs::path dir = fs::path(path).parent_path();
    std::error_code ec;
    if (!dir.empty() && !fs::is_directory(dir, ec)) {
        throw IoError(path, "cannot write: " +
                      (fs::exists(dir, ec) ? "'" + dir.string() + "' is not a directory"
                                           : "directory '" + dir.string() + "' does not exist"));
    }
#ifndef _WIN32
    const std::string d = dir.empty() ? std::string(".") : dir.string();
    if (::access(d.c_str(), W_OK | X_OK) != 0)
        throw IoError(path, "cannot write: directory '" + d + "': " + std::strerror(errno));
#endif
    if (fs::is_directory(fs::path(path), ec)) throw IoError(path, "cannot write: is a directory");
}

void check_mesh_output(const std::string& path) {
    mesh_format(path);
    check_output_location(path);
}

void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& body) {
    namespace fs = std::filesystem;
    check_output_location(path);
    if (is_special_file(path)) {
        // A temporary renamed over a device or a pipe would replace it with a regular file
        // (/dev/null itself): such a target is written in place.
        std::ofstream out(path, std::ios::binary);
        if (!out) throw IoError(path, std::string("cannot open for writing: ") + std::strerror(errno));
        body(out);
        const std::string failure = close_stream(out);
        if (!failure.empty()) throw IoError(path, "write failed: " + failure);
        return;
    }

    const std::string temp =
        path + ".tmp-" + std::to_string(process_id()) + "-" + std::to_string(temp_counter.fetch_add(1));
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    if (!out) throw IoError(path, "cannot create '" + temp + "': " + std::strerror(errno));
    const auto discard = [&] {
        out.close();
        std::error_code ignored;
        fs::remove(temp, ignored);
    };
    try {
        body(out);
    } catch (...) {
        discard();
        throw;
    }
    const std::string failure = close_stream(out);
    if (!failure.empty()) {
        discard();
        throw IoError(path, "write failed: " + failure);
    }
    std::error_code ec;
    fs::rename(temp, path, ec);
    if (ec) {
        discard();
        throw IoError(path, "cannot replace it with the new file: " + ec.message());
    }
}

namespace {

// Collects output text or bytes and hands them to the stream in large blocks.
class OutputBuffer {
public:
    // Callers check for a flush after each record, so the buffer exceeds kFlushBytes by at most
    // one record (well under 256 bytes).
    explicit OutputBuffer(std::ostream& os) : os_(os) { buffer_.reserve(kFlushBytes + 256); }
    OutputBuffer(const OutputBuffer&) = delete;
    OutputBuffer& operator=(const OutputBuffer&) = delete;

    void text(std::string_view s) {
        buffer_.append(s.data(), s.size());
        maybe_flush();
    }
    void character(char c) { buffer_.push_back(c); }
    // The shortest decimal text that reads back as exactly `v`.
    void number(float v) {
        char digits[32];
        const auto result = std::to_chars(digits, digits + sizeof digits, v);
        buffer_.append(digits, result.ptr);
    }
    void number(std::uint64_t v) {
        char digits[24];
        const auto result = std::to_chars(digits, digits + sizeof digits, v);
        buffer_.append(digits, result.ptr);
    }
    // " a b c" for each value (colours, indices plus `base`).
    template <class T, std::size_t N>
    void numbers(const std::array<T, N>& values, std::uint64_t base = 0) {
        for (T v : values) {
            character(' ');
            number(std::uint64_t{v} + base);
        }
    }
    // "x y z"
    void coordinates(const Vec3& p) {
        number(p.x);
        character(' ');
        number(p.y);
        character(' ');
        number(p.z);
    }
    // Little-endian bytes of v, whatever the machine's byte order.
    template <class T>
    void little_endian(T v) {
        unsigned char bytes[sizeof(T)];
        std::memcpy(bytes, &v, sizeof(T));
        const std::uint16_t one = 1;
        unsigned char first = 0;
        std::memcpy(&first, &one, 1);
        if (first != 1) std::reverse(bytes, bytes + sizeof(T));
        buffer_.append(reinterpret_cast<const char*>(bytes), sizeof(T));
    }
    void maybe_flush() {
        if (buffer_.size() >= kFlushBytes) flush();
    }
    void flush() {
        os_.write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
        buffer_.clear();
    }

private:
    // Block size handed to the stream: large enough to make per-call costs vanish.
    static constexpr std::size_t kFlushBytes = std::size_t{1} << 20;
    std::ostream& os_;
    std::string buffer_;
};

void write_ply(std::ostream& os, const IndexedMesh& mesh, const MeshWriteOptions& options) {
    const bool colored = !options.colors.empty();
    OutputBuffer out(os);
    out.text(options.ply_ascii ? "ply\nformat ascii 1.0\n" : "ply\nformat binary_little_endian 1.0\n");
    out.text("element vertex ");
    out.number(static_cast<std::uint64_t>(mesh.positions.size()));
    out.text("\nproperty float x\nproperty float y\nproperty float z\n");
    if (colored) out.text("property uchar red\nproperty uchar green\nproperty uchar blue\n");
    out.text("element face ");
    out.number(static_cast<std::uint64_t>(mesh.triangles.size()));
    out.text("\nproperty list uchar int vertex_indices\nend_header\n");

    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        const Vec3& p = mesh.positions[i];
        if (options.ply_ascii) {
            out.coordinates(p);
            if (colored) out.numbers(options.colors[i]);
            out.character('\n');
        } else {
            out.little_endian(p.x);
            out.little_endian(p.y);
            out.little_endian(p.z);
            if (colored)
                for (std::uint8_t c : options.colors[i]) out.character(static_cast<char>(c));
        }
        out.maybe_flush();
    }
    for (const auto& t : mesh.triangles) {
        if (options.ply_ascii) {
            out.character('3');
            out.numbers(t);
            out.character('\n');
        } else {
            out.character(3);
            for (std::uint32_t v : t) out.little_endian(static_cast<std::int32_t>(v));
        }
        out.maybe_flush();
    }
    out.flush();
}

void write_obj(std::ostream& os, const IndexedMesh& mesh) {
    OutputBuffer out(os);
    // The counts, for people; also keeps the file of an empty mesh from being empty.
    out.text("# ");
    out.number(static_cast<std::uint64_t>(mesh.positions.size()));
    out.text(" vertices, ");
    out.number(static_cast<std::uint64_t>(mesh.triangles.size()));
    out.text(" triangles\n");
    for (const Vec3& p : mesh.positions) {
        out.text("v ");
        out.coordinates(p);
        out.character('\n');
        out.maybe_flush();
    }
    for (const auto& t : mesh.triangles) {
        out.character('f');
        out.numbers(t, 1);  // OBJ indices are 1-based
        out.character('\n');
        out.maybe_flush();
    }
    out.flush();
}

void write_off(std::ostream& os, const IndexedMesh& mesh, const MeshWriteOptions& options) {
    const bool colored = !options.colors.empty();
    OutputBuffer out(os);
    out.text(colored ? "COFF\n" : "OFF\n");
    out.number(static_cast<std::uint64_t>(mesh.positions.size()));
    out.character(' ');
    out.number(static_cast<std::uint64_t>(mesh.triangles.size()));
    out.text(" 0\n");
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        const Vec3& p = mesh.positions[i];
        out.coordinates(p);
        if (colored) {
            out.numbers(options.colors[i]);
            out.text(" 255");  // COFF colours are RGBA; opaque
        }
        out.character('\n');
        out.maybe_flush();
    }
    for (const auto& t : mesh.triangles) {
        out.character('3');
        out.numbers(t);
        out.character('\n');
        out.maybe_flush();
    }
    out.flush();
}

// Refuses meshes no reader could take back; names the offending element.
void check_writable(const std::string& path, const IndexedMesh& mesh, const MeshWriteOptions& options) {
    const std::string where = "write_mesh(" + path + "): ";
    const std::size_t n = mesh.positions.size();
    if (n > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
        throw InputError(where + "mesh has " + std::to_string(n) +
                         " vertices, more than PLY's int indices can address");
    if (!options.colors.empty() && options.colors.size() != n)
        throw ParameterError("colors", where + "options.colors has " + std::to_string(options.colors.size()) + " entries for " +
                             std::to_string(n) + " vertices");
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3& p = mesh.positions[i];
        if (!is_finite(p)) throw InputError(where + "mesh.positions[" + std::to_string(i) + "] is not finite");
    }
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
        for (std::uint32_t v : mesh.triangles[t])
            if (v >= n)
                throw InputError(where + "mesh.triangles[" + std::to_string(t) + "] uses vertex " + std::to_string(v) +
                                 " of " + std::to_string(n));
}

MeshFormat mesh_format(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (ext == ".ply") return MeshFormat::ply;
    if (ext == ".obj") return MeshFormat::obj;
    if (ext == ".off") return MeshFormat::off;
    throw IoError(path, "unknown mesh format " + (ext.empty() ? std::string("(no extension)") : "'" + ext + "'") +
                  "; expected .ply, .obj or .off");
}

}  // namespace

void write_mesh(const std::string& path, const IndexedMesh& mesh, const MeshWriteOptions& options) {
    const MeshFormat format = mesh_format(path);
    check_writable(path, mesh, options);
    write_file_atomically(path, [&](std::ostream& os) {
        switch (format) {
            case MeshFormat::ply:
                write_ply(os, mesh, options);
                break;
            case MeshFormat::obj:
                write_obj(os, mesh);
                break;
            case MeshFormat::off:
                write_off(os, mesh, options);
                break;
        }
    });
}

IndexedMesh read_mesh(const std::string& path) {
    FileGeometry g = read_geometry(path, ReadFaces::yes);
    for (std::size_t i = 0; i < g.positions.size(); ++i) {
        const Vec3& p = g.positions[i];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throw IoError(path, "vertex " + std::to_string(i) + " has a non-finite coordinate");
    }
    IndexedMesh mesh;
    mesh.triangles = io_detail::fan_triangles(g);
    mesh.positions = std::move(g.positions);
    return mesh;
}

}  // namespace nmesh
