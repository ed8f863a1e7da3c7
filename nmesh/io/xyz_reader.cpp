// nmesh/io/xyz_reader.cpp — the text point reader (.xyz .txt .pts .csv): one point per line.
#include "nmesh/io/format_readers.h"

namespace nmesh::io_detail {
namespace {

bool is_field_separator(char c) { return kFieldSeparators[static_cast<unsigned char>(c)]; }

// Reads the next field of a text point line (from p on) as a coordinate and moves p past it;
// false when the line has no more fields. Common numbers are parsed in the one scan.
bool next_coordinate(const InputFile& in, std::string_view line, const char*& p, float& out) {
    const char* const end = line.data() + line.size();
    while (p != end && is_field_separator(*p)) ++p;
    if (p == end) return false;
    const char* q = p;
    if (scan_float_fast(q, end, out) && (q == end || is_field_separator(*q))) {
        p = q;
        return true;
    }
    const char* token_end = p;
    while (token_end != end && !is_field_separator(*token_end)) ++token_end;
    out = parse_coordinate(in, line, std::string_view(p, static_cast<std::size_t>(token_end - p)));
    p = token_end;
    return true;
}

}  // namespace

void read_xyz(InputFile& in, bool pts, FileGeometry& g) {
    g.format = "xyz";
    g.encoding = "text";
    skip_byte_order_mark(in);
    std::vector<Vec3>& out = g.positions;
    bool first_data_line = true;
    std::string_view line;
    while (in.next_line(line)) {
        line = without_comment(line);
        const char* p = line.data();
        Vec3 v;
        int found = 0;
        while (found < 3 && next_coordinate(in, line, p, v[found])) ++found;
        if (found == 0) continue;
        if (found < 3) {
            std::string_view rest = line;
            std::int64_t count = 0;
            const bool single_integer = found == 1 && parse_int(next_token(rest, kFieldSeparators), count);
            if (pts && first_data_line && single_integer) {
                first_data_line = false;  // the PTS point count; not checked
                continue;
            }
            in.fail_line("expected 3 numbers (x y z), found " + std::to_string(found));
        }
        first_data_line = false;
        out.push_back(v);
    }
}

}  // namespace nmesh::io_detail
