// nmesh/io/obj_reader.cpp — the Wavefront OBJ reader: "v" lines and "f" faces.
#include "nmesh/io/format_readers.h"

namespace nmesh::io_detail {
void read_obj(InputFile& in, ReadFaces faces, FileGeometry& g) {
    g.format = "obj";
    g.encoding = "text";
    skip_byte_order_mark(in);
    std::string_view line;
    while (in.next_line(line)) {
        line = without_comment(line);
        std::string_view rest = line;
        const std::string_view key = next_token(rest);
        if (key == "v") {
            Vec3 p;
            for (int c = 0; c < 3; ++c) {
                const std::string_view t = next_token(rest);
                if (t.empty()) in.fail_line("a 'v' line needs 3 coordinates, found " + std::to_string(c));
                p[c] = parse_coordinate(in, line, t);
            }
            g.positions.push_back(p);
        } else if (key == "f") {
            ++g.face_count;
            if (faces == ReadFaces::no) continue;
            begin_faces(g);
            const std::size_t first = g.face_indices.size();
            const std::uint64_t defined = g.positions.size();
            for (std::string_view corner = next_token(rest); !corner.empty(); corner = next_token(rest)) {
                const std::string_view v = corner.substr(0, corner.find('/'));
                std::int64_t index = 0;
                if (!parse_int(v, index)) {
                    if (has_binary_byte(line)) in.fail_line("binary data, not text");
                    if (is_integer_text(v))
                        in.fail_line("vertex index " + std::string(v) + " is out of range (" + std::to_string(defined) +
                                     " vertices are defined above this line)");
                    in.fail_line("face corner " + quote_token(corner) + " does not start with a vertex index");
                }
                if (index == 0) in.fail_line("vertex index 0 (OBJ indices start at 1)");
                // Negative indices count back from the latest vertex: -1 is the last one defined.
                const std::int64_t resolved = index > 0 ? index - 1 : static_cast<std::int64_t>(defined) + index;
                if (resolved < 0 || static_cast<std::uint64_t>(resolved) >= defined)
                    in.fail_line("vertex index " + std::to_string(index) + " is out of range (" +
                                 std::to_string(defined) + " vertices are defined above this line)");
                g.face_indices.push_back(static_cast<std::uint32_t>(resolved));
            }
            const std::size_t corners = g.face_indices.size() - first;
            if (corners < 3) in.fail_line("a face needs at least 3 corners, found " + std::to_string(corners));
            end_face(g);
        }
    }
}

}  // namespace nmesh::io_detail
