// nmesh/io/ply_reader.cpp — the PLY reader: ascii, binary_little_endian and binary_big_endian bodies, any numeric
// property type, a fast path for float x, y, z records in the machine's byte order.
#include "nmesh/io/format_readers.h"

namespace nmesh::io_detail {
namespace {

enum class PlyType : std::uint8_t { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

struct PlyTypeName {
    std::string_view name;
    PlyType type;
};
constexpr PlyTypeName kPlyTypeNames[] = {
    {"char", PlyType::int8},       {"int8", PlyType::int8},       {"uchar", PlyType::uint8},
    {"uint8", PlyType::uint8},     {"short", PlyType::int16},     {"int16", PlyType::int16},
    {"ushort", PlyType::uint16},   {"uint16", PlyType::uint16},   {"int", PlyType::int32},
    {"int32", PlyType::int32},     {"uint", PlyType::uint32},     {"uint32", PlyType::uint32},
    {"float", PlyType::float32},   {"float32", PlyType::float32}, {"double", PlyType::float64},
    {"float64", PlyType::float64},
};

std::size_t type_size(PlyType t) {
    switch (t) {
        case PlyType::int8:
        case PlyType::uint8:
            return 1;
        case PlyType::int16:
        case PlyType::uint16:
            return 2;
        case PlyType::int32:
        case PlyType::uint32:
        case PlyType::float32:
            return 4;
        case PlyType::float64:
            return 8;
    }
    return 0;
}

bool is_integer(PlyType t) { return t != PlyType::float32 && t != PlyType::float64; }

template <class T>
T load(const unsigned char* p, bool swap) {
    unsigned char bytes[sizeof(T)];
    if (swap) {
        for (std::size_t i = 0; i < sizeof(T); ++i) bytes[i] = p[sizeof(T) - 1 - i];
    } else {
        std::memcpy(bytes, p, sizeof(T));
    }
    T v;
    std::memcpy(&v, bytes, sizeof(T));
    return v;
}

float load_coordinate(const unsigned char* p, PlyType t, bool swap) {
    switch (t) {
        case PlyType::int8:
            return static_cast<float>(load<std::int8_t>(p, swap));
        case PlyType::uint8:
            return static_cast<float>(load<std::uint8_t>(p, swap));
        case PlyType::int16:
            return static_cast<float>(load<std::int16_t>(p, swap));
        case PlyType::uint16:
            return static_cast<float>(load<std::uint16_t>(p, swap));
        case PlyType::int32:
            return static_cast<float>(load<std::int32_t>(p, swap));
        case PlyType::uint32:
            return static_cast<float>(load<std::uint32_t>(p, swap));
        case PlyType::float32:
            return load<float>(p, swap);
        case PlyType::float64:
            return to_float(load<double>(p, swap));
    }
    return 0.0f;
}

// Precondition: is_integer(t).
std::int64_t load_integer(const unsigned char* p, PlyType t, bool swap) {
    switch (t) {
        case PlyType::int8:
            return load<std::int8_t>(p, swap);
        case PlyType::uint8:
            return load<std::uint8_t>(p, swap);
        case PlyType::int16:
            return load<std::int16_t>(p, swap);
        case PlyType::uint16:
            return load<std::uint16_t>(p, swap);
        case PlyType::int32:
            return load<std::int32_t>(p, swap);
        case PlyType::uint32:
            return load<std::uint32_t>(p, swap);
        case PlyType::float32:
        case PlyType::float64:
            break;
    }
    assert(false && "load_integer on a floating-point type");
    return 0;
}

struct PlyProperty {
    std::string name;
    PlyType type = PlyType::float32;  // the value type; for a list, the item type
    bool is_list = false;
    PlyType count_type = PlyType::uint8;
};

struct PlyElement {
    std::string name;
    std::uint64_t count = 0;
    std::vector<PlyProperty> properties;
    std::vector<std::string> declarations;  // the property lines, for PlyElementInfo
};

enum class PlyEncoding { ascii, binary_little_endian, binary_big_endian };

struct PlyHeader {
    PlyEncoding encoding = PlyEncoding::ascii;
    std::vector<PlyElement> elements;
};

const char* encoding_name(PlyEncoding e) {
    switch (e) {
        case PlyEncoding::ascii:
            return "ascii";
        case PlyEncoding::binary_little_endian:
            return "binary_little_endian";
        case PlyEncoding::binary_big_endian:
            return "binary_big_endian";
    }
    return "";
}

PlyType parse_ply_type(const InputFile& in, std::string_view name) {
    for (const PlyTypeName& entry : kPlyTypeNames)
        if (entry.name == name) return entry.type;
    if (name.empty()) in.fail_line("property line without a type");
    in.fail_line("unknown property type " + quote_token(name));
}

PlyHeader read_ply_header(InputFile& in) {
    in.fill(4);
    const auto* magic = in.data();
    if (in.available() < 4 || std::memcmp(magic, "ply", 3) != 0 || (magic[3] != '\n' && magic[3] != '\r'))
        in.fail("not a PLY file (it does not start with a 'ply' line)");
    std::string_view line;
    in.next_line(line);

    PlyHeader h;
    bool have_format = false;
    for (;;) {
        if (!in.next_line(line)) in.fail("missing end_header (the file ends inside the PLY header)");
        std::string_view rest = line;
        const std::string_view key = next_token(rest);
        if (key.empty() || key == "comment" || key == "obj_info") continue;
        if (key == "end_header") break;
        if (key == "format") {
            const std::string_view encoding = next_token(rest);
            const std::string_view version = next_token(rest);
            if (encoding == "ascii")
                h.encoding = PlyEncoding::ascii;
            else if (encoding == "binary_little_endian")
                h.encoding = PlyEncoding::binary_little_endian;
            else if (encoding == "binary_big_endian")
                h.encoding = PlyEncoding::binary_big_endian;
            else
                in.fail_line("unknown PLY format " + quote_token(encoding));
            if (version != "1.0" && version != "1")
                in.fail_line("unsupported PLY version " + quote_token(version) + " (only 1.0 is known)");
            have_format = true;
        } else if (key == "element") {
            PlyElement e;
            e.name = std::string(next_token(rest));
            const std::string_view count = next_token(rest);
            const char* last = count.data() + count.size();
            const auto [end, ec] = std::from_chars(count.data(), last, e.count);
            if (e.name.empty() || count.empty() || ec != std::errc() || end != last)
                in.fail_line("bad element line (expected 'element <name> <count>'): " + quote_token(line));
            h.elements.push_back(std::move(e));
        } else if (key == "property") {
            if (h.elements.empty()) in.fail_line("property line before any element line");
            PlyProperty p;
            std::string_view declaration = rest;  // "float x", "list uchar int vertex_indices"
            while (!declaration.empty() && is_blank(declaration.front())) declaration.remove_prefix(1);
            while (!declaration.empty() && is_blank(declaration.back())) declaration.remove_suffix(1);
            const std::string_view type = next_token(rest);
            if (type == "list") {
                p.is_list = true;
                const std::string_view count_type = next_token(rest);
                p.count_type = parse_ply_type(in, count_type);
                if (!is_integer(p.count_type))
                    in.fail_line("list count type " + quote_token(count_type) + " is not an integer type");
                p.type = parse_ply_type(in, next_token(rest));
            } else {
                p.type = parse_ply_type(in, type);
            }
            p.name = std::string(next_token(rest));
            if (p.name.empty()) in.fail_line("property line without a name");
            PlyElement& e = h.elements.back();
            e.properties.push_back(std::move(p));
            e.declarations.emplace_back(declaration);
        } else {
            in.fail_line("unknown PLY header keyword " + quote_token(key));
        }
    }
    if (!have_format) in.fail("the PLY header has no 'format' line");
    return h;
}

// What the reader does with one property of an element.
enum class Role : std::uint8_t { skip, x, y, z, indices };

std::string declared_records(const PlyHeader& h) {
    std::string s;
    for (const PlyElement& e : h.elements) {
        if (!s.empty()) s += ", ";
        s += std::to_string(e.count) + " '" + e.name + "'";
    }
    return s.empty() ? "no elements" : s;
}

class PlyBodyReader {
public:
    PlyBodyReader(InputFile& in, const PlyHeader& h, ReadFaces faces, FileGeometry& out)
        : in_(in), h_(h), faces_(faces), out_(out) {}

    void read() {
        check_body_size();
        plan();
        for (std::size_t i = 0; i < h_.elements.size(); ++i) {
            if (h_.encoding == PlyEncoding::ascii)
                read_ascii_element(h_.elements[i], roles_[i]);
            else
                read_binary_element(h_.elements[i], roles_[i]);
        }
        check_nothing_follows();
    }

private:
    // Finds the vertex and face elements and assigns a role to every property.
    void plan() {
        roles_.resize(h_.elements.size());
        bool have_vertex = false, have_face = false;
        for (std::size_t i = 0; i < h_.elements.size(); ++i) {
            const PlyElement& e = h_.elements[i];
            roles_[i].assign(e.properties.size(), Role::skip);
            if (e.name == "vertex" && !have_vertex) {
                have_vertex = true;
                vertex_count_ = e.count;
                plan_vertex(e, roles_[i]);
            } else if (e.name == "face" && !have_face) {
                have_face = true;
                out_.face_count = e.count;
                if (faces_ == ReadFaces::yes) plan_face(e, roles_[i]);
            }
        }
        if (!have_vertex) in_.fail("the PLY header has no 'vertex' element");
    }

    void plan_vertex(const PlyElement& e, std::vector<Role>& roles) {
        const char* names[3] = {"x", "y", "z"};
        const Role coordinate_roles[3] = {Role::x, Role::y, Role::z};
        for (int c = 0; c < 3; ++c) {
            bool found = false;
            for (std::size_t j = 0; j < e.properties.size() && !found; ++j) {
                if (e.properties[j].name != names[c]) continue;
                if (e.properties[j].is_list)
                    in_.fail(std::string("property '") + names[c] + "' of element 'vertex' is a list");
                roles[j] = coordinate_roles[c];
                found = true;
            }
            if (!found) in_.fail(std::string("element 'vertex' has no '") + names[c] + "' property");
        }
    }

    void plan_face(const PlyElement& e, std::vector<Role>& roles) {
        for (std::size_t j = 0; j < e.properties.size(); ++j) {
            const PlyProperty& p = e.properties[j];
            if (p.name != "vertex_indices" && p.name != "vertex_index") continue;
            if (!p.is_list) in_.fail("property '" + p.name + "' of element 'face' is not a list");
            if (!is_integer(p.type))
                in_.fail("property '" + p.name + "' of element 'face' does not have an integer type");
            roles[j] = Role::indices;
            if (e.count > 0) {
                // Reserve no more than the file can hold: a triangle takes at least "3 0 0 0\n"
                // (ASCII) or a count and three indices (binary).
                const std::uint64_t min_face_bytes =
                    h_.encoding == PlyEncoding::ascii ? 8 : type_size(p.count_type) + 3 * type_size(p.type);
                const auto faces = static_cast<std::size_t>(std::min(e.count, in_.remaining() / min_face_bytes + 1));
                out_.face_offsets.reserve(faces + 1);
                out_.face_indices.reserve(3 * faces);
                begin_faces(out_);
            }
            return;
        }
        if (e.count > 0) in_.fail("element 'face' has no 'vertex_indices' list property");
    }

    // Fewest bytes a record can take: its scalars and list counts (binary), or one character
    // and one separator per value (ASCII).
    std::uint64_t min_record_bytes(const PlyElement& e) const {
        std::uint64_t bytes = 0;
        for (const PlyProperty& p : e.properties) {
            if (h_.encoding == PlyEncoding::ascii)
                bytes += 2;
            else
                bytes += type_size(p.is_list ? p.count_type : p.type);
        }
        return bytes;
    }

    // Refuses counts the file cannot hold before anything is allocated on their word.
    void check_body_size() {
        const std::uint64_t body = in_.remaining();
        std::uint64_t records = 0, need = 0;
        for (const PlyElement& e : h_.elements) {
            records = saturating_add(records, e.count);
            need = saturating_add(need, saturating_mul(e.count, min_record_bytes(e)));
        }
        if (records > 0 && body == 0)
            in_.fail("header only: no data after end_header, which declares " + declared_records(h_));
        if (h_.encoding == PlyEncoding::ascii && need > 0) --need;  // the last line break may be missing
        if (need <= body) return;
        const std::string what = "the header declares " + declared_records(h_) + ", needing at least " +
                                 std::to_string(need) + " bytes, but only " + std::to_string(body) +
                                 " bytes follow the header";
        if (h_.encoding == PlyEncoding::ascii) in_.fail(what);
        in_.fail_at_offset(in_.offset(), "truncated binary body: " + what);
    }

    void check_nothing_follows() {
        if (h_.encoding == PlyEncoding::ascii) {
            std::string_view line;
            while (in_.next_line(line)) {
                if (is_blank_line(line)) continue;
                in_.fail_line("more data than the header declares (" + declared_records(h_) + ")");
            }
            return;
        }
        const std::uint64_t start = in_.offset();
        const std::uint64_t extra = in_.remaining();
        while (in_.fill(1) > 0) {
            const auto* p = in_.data();
            const std::size_t n = in_.available();
            for (std::size_t i = 0; i < n; ++i) {
                if (!is_blank(static_cast<char>(p[i])) && p[i] != '\n')
                    in_.fail_at_offset(start, std::to_string(extra) +
                                                  " bytes of data after the last record the header "
                                                  "declares (" +
                                                  declared_records(h_) + ")");
            }
            in_.consume(n);
        }
    }

    // ---- ASCII: one record per line

    void read_ascii_element(const PlyElement& e, const std::vector<Role>& roles) {
        const bool decode = std::any_of(roles.begin(), roles.end(), [](Role r) { return r != Role::skip; });
        const bool is_vertex = decode && e.name == "vertex";
        if (is_vertex) out_.positions.reserve(static_cast<std::size_t>(e.count));
        std::string_view line;
        for (std::uint64_t r = 0; r < e.count; ++r) {
            do {
                if (!in_.next_line(line))
                    in_.fail("the file ends after " + std::to_string(r) + " of " + std::to_string(e.count) + " '" +
                             e.name + "' records (line " + std::to_string(in_.line_number()) + ")");
            } while (is_blank_line(line));
            if (!decode) continue;
            const Vec3 p = read_ascii_record(e, roles, r, line);
            if (is_vertex) out_.positions.push_back(p);
        }
    }

    Vec3 read_ascii_record(const PlyElement& e, const std::vector<Role>& roles, std::uint64_t r,
                           std::string_view line) {
        const auto value = [&](std::string_view& rest) {
            const std::string_view t = next_token(rest);
            if (t.empty())
                in_.fail_line("'" + e.name + "' record " + std::to_string(r) + " has fewer values than its " +
                              std::to_string(e.properties.size()) + " properties declare");
            return t;
        };
        std::string_view rest = line;
        Vec3 p;
        for (std::size_t j = 0; j < e.properties.size(); ++j) {
            const PlyProperty& prop = e.properties[j];
            if (!prop.is_list) {
                const float v = parse_coordinate(in_, line, value(rest));
                if (roles[j] == Role::x)
                    p.x = v;
                else if (roles[j] == Role::y)
                    p.y = v;
                else if (roles[j] == Role::z)
                    p.z = v;
                continue;
            }
            const std::string_view count_token = value(rest);
            std::int64_t n = 0;
            if (!parse_int(count_token, n) || n < 0) {
                if (has_binary_byte(line)) in_.fail_line("binary data, not text");
                in_.fail_line("list count " + quote_token(count_token) + " of '" + e.name + "' record " +
                              std::to_string(r) + " is not a non-negative integer");
            }
            const auto fail = [&](const std::string& m) { in_.fail_line(m); };
            if (roles[j] == Role::indices) check_corner_count(n, r, fail);
            for (std::int64_t k = 0; k < n; ++k) {
                const std::string_view t = value(rest);
                if (roles[j] != Role::indices) {
                    parse_coordinate(in_, line, t);
                    continue;
                }
                std::int64_t index = 0;
                if (!parse_int(t, index)) {
                    if (has_binary_byte(line)) in_.fail_line("binary data, not text");
                    in_.fail_line("vertex index " + quote_token(t) +
                                  (is_integer_text(t) ? " is out of range" : " is not an integer"));
                }
                add_index(index, r, fail);
            }
            if (roles[j] == Role::indices) end_face(out_);
        }
        if (!next_token(rest).empty())
            in_.fail_line("'" + e.name + "' record " + std::to_string(r) + " has more values than its " +
                          std::to_string(e.properties.size()) + " properties declare");
        return p;
    }

    template <class Fail>
    void check_corner_count(std::int64_t n, std::uint64_t face, const Fail& fail) const {
        if (n < 3)
            fail("face " + std::to_string(face) + " has " + std::to_string(n) + " corners; a face needs at least 3");
    }

    template <class Fail>
    void add_index(std::int64_t index, std::uint64_t face, const Fail& fail) {
        if (index < 0 || static_cast<std::uint64_t>(index) >= vertex_count_)
            fail("face " + std::to_string(face) + ": vertex index " + std::to_string(index) +
                 " is out of range (the file has " + std::to_string(vertex_count_) + " vertices)");
        out_.face_indices.push_back(static_cast<std::uint32_t>(index));
    }

    // ---- binary

    [[noreturn]] void fail_truncated(const PlyElement& e, std::uint64_t r) const {
        in_.fail_at_offset(in_.offset(), "truncated binary body: the file (" + std::to_string(in_.size()) +
                                             " bytes) ends inside '" + e.name + "' record " + std::to_string(r) +
                                             " of " + std::to_string(e.count));
    }

    bool swap() const { return (h_.encoding == PlyEncoding::binary_little_endian) != host_is_little_endian(); }

    void read_binary_element(const PlyElement& e, const std::vector<Role>& roles) {
        const bool fixed =
            std::none_of(e.properties.begin(), e.properties.end(), [](const PlyProperty& p) { return p.is_list; });
        const bool decode = std::any_of(roles.begin(), roles.end(), [](Role r) { return r != Role::skip; });
        if (fixed && !decode) {
            std::uint64_t stride = 0;
            for (const PlyProperty& p : e.properties) stride += type_size(p.type);
            const std::uint64_t bytes = saturating_mul(e.count, stride);
            const std::uint64_t skipped = in_.skip(bytes);
            if (skipped < bytes) fail_truncated(e, stride == 0 ? 0 : skipped / stride);
        } else if (fixed) {
            read_fixed_vertices(e, roles);
        } else {
            walk_records(e, roles);
        }
    }

    // Vertex records without lists: a fixed stride, converted a buffer at a time, or read
    // straight into the result when they are exactly float x, y, z in the machine's byte order.
    void read_fixed_vertices(const PlyElement& e, const std::vector<Role>& roles) {
        std::size_t stride = 0;
        std::size_t offset[3] = {0, 0, 0};
        PlyType type[3] = {PlyType::float32, PlyType::float32, PlyType::float32};
        for (std::size_t j = 0; j < e.properties.size(); ++j) {
            const int c = roles[j] == Role::x ? 0 : roles[j] == Role::y ? 1 : roles[j] == Role::z ? 2 : -1;
            if (c >= 0) {
                offset[c] = stride;
                type[c] = e.properties[j].type;
            }
            stride += type_size(e.properties[j].type);
        }
        const auto count = static_cast<std::size_t>(e.count);
        const bool swap_bytes = swap();
        std::vector<Vec3>& out = out_.positions;
        const bool exact_float_xyz = stride == 12 && !swap_bytes && offset[0] == 0 && offset[1] == 4 &&
                                     offset[2] == 8 && type[0] == PlyType::float32 && type[1] == PlyType::float32 &&
                                     type[2] == PlyType::float32;
        if (exact_float_xyz) {
            const std::size_t start = out.size();
            out.resize(start + count);
            const std::size_t got = in_.read_into(out.data() + start, count * stride);
            if (got < count * stride) fail_truncated(e, got / stride);
            return;
        }
        const bool native_floats =
            !swap_bytes && type[0] == PlyType::float32 && type[1] == PlyType::float32 && type[2] == PlyType::float32;
        const std::size_t start = out.size();
        out.resize(start + count);
        Vec3* q = out.data() + start;
        const std::size_t per_chunk = std::max<std::size_t>(1, kBufferBytes / stride);
        for (std::size_t done = 0; done < count;) {
            const std::size_t k = std::min(count - done, per_chunk);
            if (in_.fill(k * stride) < k * stride) fail_truncated(e, done + in_.available() / stride);
            const unsigned char* p = in_.data();
            if (native_floats) {
                for (std::size_t i = 0; i < k; ++i, p += stride, ++q) {
                    std::memcpy(&q->x, p + offset[0], 4);
                    std::memcpy(&q->y, p + offset[1], 4);
                    std::memcpy(&q->z, p + offset[2], 4);
                }
            } else {
                for (std::size_t i = 0; i < k; ++i, p += stride, ++q)
                    *q = {load_coordinate(p + offset[0], type[0], swap_bytes),
                          load_coordinate(p + offset[1], type[1], swap_bytes),
                          load_coordinate(p + offset[2], type[2], swap_bytes)};
            }
            in_.consume(k * stride);
            done += k;
        }
    }

    // Records with lists: property by property.
    void walk_records(const PlyElement& e, const std::vector<Role>& roles) {
        const bool swap_bytes = swap();
        const bool is_vertex =
            e.name == "vertex" && std::any_of(roles.begin(), roles.end(), [](Role r) { return r == Role::x; });
        if (is_vertex) out_.positions.reserve(static_cast<std::size_t>(e.count));
        for (std::uint64_t r = 0; r < e.count; ++r) {
            Vec3 p;
            for (std::size_t j = 0; j < e.properties.size(); ++j) {
                const PlyProperty& prop = e.properties[j];
                if (!prop.is_list) {
                    const std::size_t size = type_size(prop.type);
                    need(size, e, r);
                    if (roles[j] == Role::x)
                        p.x = load_coordinate(in_.data(), prop.type, swap_bytes);
                    else if (roles[j] == Role::y)
                        p.y = load_coordinate(in_.data(), prop.type, swap_bytes);
                    else if (roles[j] == Role::z)
                        p.z = load_coordinate(in_.data(), prop.type, swap_bytes);
                    in_.consume(size);
                    continue;
                }
                const std::uint64_t at = in_.offset();
                need(type_size(prop.count_type), e, r);
                const std::int64_t n = load_integer(in_.data(), prop.count_type, swap_bytes);
                in_.consume(type_size(prop.count_type));
                const auto fail = [&](const std::string& m) { in_.fail_at_offset(at, m); };
                if (n < 0)
                    fail("negative list count " + std::to_string(n) + " in '" + e.name + "' record " +
                         std::to_string(r));
                const std::size_t item = type_size(prop.type);
                const std::uint64_t bytes = saturating_mul(static_cast<std::uint64_t>(n), item);
                if (roles[j] != Role::indices) {
                    if (in_.skip(bytes) < bytes) fail_truncated(e, r);
                    continue;
                }
                check_corner_count(n, r, fail);
                need(static_cast<std::size_t>(bytes), e, r);
                const unsigned char* q = in_.data();
                for (std::int64_t k = 0; k < n; ++k, q += item)
                    add_index(load_integer(q, prop.type, swap_bytes), r, fail);
                in_.consume(static_cast<std::size_t>(bytes));
                end_face(out_);
            }
            if (is_vertex) out_.positions.push_back(p);
        }
    }

    void need(std::size_t bytes, const PlyElement& e, std::uint64_t r) {
        if (in_.available() < bytes && in_.fill(bytes) < bytes) fail_truncated(e, r);
    }

    InputFile& in_;
    const PlyHeader& h_;
    ReadFaces faces_;
    FileGeometry& out_;
    std::vector<std::vector<Role>> roles_;
    std::uint64_t vertex_count_ = 0;
};

}  // namespace

void read_ply(InputFile& in, ReadFaces faces, FileGeometry& g) {
    const PlyHeader h = read_ply_header(in);
    g.format = "ply";
    g.encoding = encoding_name(h.encoding);
    for (const PlyElement& e : h.elements) g.elements.push_back({e.name, e.count, e.declarations});
    PlyBodyReader(in, h, faces, g).read();
}

}  // namespace nmesh::io_detail
