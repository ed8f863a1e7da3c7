// nmesh/io/off_reader.cpp — the ASCII OFF reader.
#include "nmesh/io/format_readers.h"

namespace nmesh::io_detail {
namespace {

// The next line that is neither blank nor a comment, or false at the end of the file.
bool next_data_line(InputFile& in, std::string_view& line) {
    while (in.next_line(line)) {
        line = without_comment(line);
        if (!is_blank_line(line)) return true;
    }
    return false;
}

std::uint64_t parse_off_count(const InputFile& in, std::string_view token, const char* what) {
    std::int64_t n = 0;
    if (token.empty()) in.fail_line(std::string("missing ") + what + " count in the OFF header");
    if (!parse_int(token, n) || n < 0)
        in.fail_line(std::string("bad ") + what + " count " + quote_token(token) + " in the OFF header");
    return static_cast<std::uint64_t>(n);
}

}  // namespace

void read_off(InputFile& in, ReadFaces faces, FileGeometry& g) {
    g.format = "off";
    g.encoding = "text";
    skip_byte_order_mark(in);
    std::string_view line;
    if (!next_data_line(in, line)) in.fail("no OFF header");
    std::string_view rest = line;
    const std::string_view keyword = next_token(rest);
    if (!is_off_keyword(keyword)) in.fail_line("not an OFF file (the header keyword is " + quote_token(keyword) + ")");
    std::string_view counts = rest;
    std::string_view probe = rest;
    const std::string_view after = next_token(probe);
    if (after == "BINARY") in.fail_line("binary OFF is not supported");
    if (after.empty()) {
        if (!next_data_line(in, line)) in.fail("the OFF header has no vertex and face counts");
        counts = line;
    }
    const std::uint64_t nv = parse_off_count(in, next_token(counts), "vertex");
    const std::uint64_t nf = parse_off_count(in, next_token(counts), "face");
    g.face_count = nf;
    // Fewest bytes: "0 0 0\n" per vertex and "3 0 0 0\n" per face.
    const std::uint64_t need = saturating_add(saturating_mul(nv, 6), saturating_mul(nf, 8));
    if (need > saturating_add(in.remaining(), 1))
        in.fail_line("the header declares " + count_text(nv, "vertices") + " and " + count_text(nf, "faces") +
                     ", needing at least " + std::to_string(need) + " bytes, but only " +
                     std::to_string(in.remaining()) + " bytes follow");
    g.positions.reserve(static_cast<std::size_t>(nv));
    for (std::uint64_t i = 0; i < nv; ++i) {
        if (!next_data_line(in, line))
            in.fail("the file ends after " + std::to_string(i) + " of " + count_text(nv, "vertex lines"));
        std::string_view r = line;
        Vec3 p;
        for (int c = 0; c < 3; ++c) {
            const std::string_view t = next_token(r);
            if (t.empty()) in.fail_line("a vertex line needs 3 coordinates, found " + std::to_string(c));
            p[c] = parse_coordinate(in, line, t);
        }
        g.positions.push_back(p);
    }
    if (faces == ReadFaces::yes && nf > 0) {
        g.face_offsets.reserve(static_cast<std::size_t>(nf) + 1);
        g.face_indices.reserve(3 * static_cast<std::size_t>(nf));
        begin_faces(g);
    }
    for (std::uint64_t f = 0; f < nf; ++f) {
        if (!next_data_line(in, line))
            in.fail("the file ends after " + std::to_string(f) + " of " + count_text(nf, "face lines"));
        if (faces == ReadFaces::no) continue;
        std::string_view r = line;
        const std::string_view count_token = next_token(r);
        std::int64_t n = 0;
        if (!parse_int(count_token, n) || n < 3)
            in.fail_line("face " + std::to_string(f) + ": corner count " + quote_token(count_token) +
                         " is not an integer >= 3");
        for (std::int64_t k = 0; k < n; ++k) {
            const std::string_view t = next_token(r);
            std::int64_t index = 0;
            if (t.empty())
                in.fail_line("face " + std::to_string(f) + " has fewer than " + std::to_string(n) + " indices");
            if (!parse_int(t, index))
                in.fail_line("vertex index " + quote_token(t) +
                             (is_integer_text(t) ? " is out of range" : " is not an integer"));
            if (index < 0 || static_cast<std::uint64_t>(index) >= nv)
                in.fail_line("face " + std::to_string(f) + ": vertex index " + std::to_string(index) +
                             " is out of range (the file has " + count_text(nv, "vertices") + ")");
            g.face_indices.push_back(static_cast<std::uint32_t>(index));
        }
        end_face(g);  // anything after the indices (a colour) is ignored
    }
    if (next_data_line(in, line))
        in.fail_line("more lines than the header declares (" + count_text(nv, "vertices") + ", " +
                     count_text(nf, "faces") + ")");
}

}  // namespace nmesh::io_detail
