// nmesh/point_reader.cpp — the PLY, text (XYZ), OBJ and OFF readers behind read_points,
// inspect_file and read_geometry.
#include "nmesh/io.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cerrno>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string_view>
#include <system_error>
#include <type_traits>
#include <utility>

#include "nmesh/error.h"

namespace nmesh {
namespace {

static_assert(sizeof(Vec3) == 12 && std::is_trivially_copyable_v<Vec3>,
              "the binary PLY fast path reads float x, y, z records straight into Vec3s");

// Read granularity: large enough that the per-call cost of fread vanishes, small enough to stay
// in cache while a chunk is converted.
constexpr std::size_t kBufferBytes = std::size_t{1} << 20;

// Longest accepted text line. No real point, vertex or face line comes near it; a longer "line"
// means binary data or a file without line breaks.
constexpr std::size_t kMaxLineBytes = kBufferBytes;

// ---------------------------------------------------------------------------------------------
// Small helpers

std::uint64_t saturating_add(std::uint64_t a, std::uint64_t b) {
    return a > std::numeric_limits<std::uint64_t>::max() - b ? std::numeric_limits<std::uint64_t>::max()
                                                             : a + b;
}

std::uint64_t saturating_mul(std::uint64_t a, std::uint64_t b) {
    return (a != 0 && b > std::numeric_limits<std::uint64_t>::max() / a)
               ? std::numeric_limits<std::uint64_t>::max()
               : a * b;
}

bool host_is_little_endian() {
    const std::uint16_t one = 1;
    unsigned char first = 0;
    std::memcpy(&first, &one, 1);
    return first == 1;
}

// A token as it can be shown inside a one-line message: quoted, non-printable bytes escaped,
// long tokens shortened.
std::string quote_token(std::string_view token) {
    constexpr std::size_t kShown = 32;  // enough to recognise the token, short enough for one line
    std::string s = "'";
    for (std::size_t i = 0; i < token.size() && i < kShown; ++i) {
        const auto c = static_cast<unsigned char>(token[i]);
        if (c >= 0x20 && c < 0x7f) {
            s += static_cast<char>(c);
        } else {
            char hex[8];
            std::snprintf(hex, sizeof hex, "\\x%02x", c);
            s += hex;
        }
    }
    if (token.size() > kShown) s += "...";
    return s + "'";
}

// True if `line` holds a byte no text file has (a control character other than tab, CR, FF, VT).
bool has_binary_byte(std::string_view line) {
    for (char ch : line) {
        const auto c = static_cast<unsigned char>(ch);
        if ((c < 0x20 && c != '\t' && c != '\r' && c != '\f' && c != '\v') || c == 0x7f) return true;
    }
    return false;
}

float to_float(long double v) {
    if (v > std::numeric_limits<float>::max()) return std::numeric_limits<float>::infinity();
    if (v < -std::numeric_limits<float>::max()) return -std::numeric_limits<float>::infinity();
    return static_cast<float>(v);
}

std::string_view without_plus(std::string_view t) {
    if (t.size() > 1 && t[0] == '+' && t[1] != '+' && t[1] != '-') t.remove_prefix(1);
    return t;
}

bool is_digit(char c) { return c >= '0' && c <= '9'; }

// Powers of ten a double holds exactly (5^22 < 2^53).
constexpr double kExactPowersOfTen[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                        1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                        1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

// Clinger's fast path, several times faster than std::from_chars<float> here. A decimal whose
// digits form an integer m <= 2^53 and whose decimal exponent is within +-22 becomes a double with
// one correctly rounded operation (m and 10^|e| are exact); rounding that double to float is then
// correct unless it lies exactly halfway between two floats (checked), because no such halfway
// point can lie strictly between a value and its nearest double. False when the path does not
// apply (the caller falls back to std::from_chars), including non-numbers, subnormal and
// out-of-range results. On success `first` is moved past the number.
bool scan_float_fast(const char*& first, const char* const end, float& out) {
    const char* p = first;
    bool negative = false;
    if (p != end && (*p == '-' || *p == '+')) negative = *p++ == '-';
    std::uint64_t mantissa = 0;  // wraps harmlessly beyond 19 digits; such tokens are refused below
    const char* const integer_begin = p;
    while (p != end && is_digit(*p)) mantissa = mantissa * 10 + static_cast<unsigned>(*p++ - '0');
    std::ptrdiff_t digits = p - integer_begin;
    std::ptrdiff_t exponent = 0;
    if (p != end && *p == '.') {
        const char* const fraction_begin = ++p;
        while (p != end && is_digit(*p)) mantissa = mantissa * 10 + static_cast<unsigned>(*p++ - '0');
        exponent = fraction_begin - p;
        digits += p - fraction_begin;
    }
    if (digits == 0 || digits > 19) return false;  // 19 digits always fit in 64 bits
    if (p != end && (*p == 'e' || *p == 'E')) {
        ++p;
        bool negative_exponent = false;
        if (p != end && (*p == '-' || *p == '+')) negative_exponent = *p++ == '-';
        const char* const exponent_begin = p;
        int e = 0;
        while (p != end && is_digit(*p) && p - exponent_begin < 4) e = e * 10 + (*p++ - '0');
        if (p == exponent_begin) return false;
        exponent += negative_exponent ? -e : e;
    }
    if (mantissa == 0) {
        out = negative ? -0.0f : 0.0f;
        first = p;
        return true;
    }
    if (mantissa > (std::uint64_t{1} << 53) || exponent < -22 || exponent > 22) return false;
    double d = static_cast<double>(mantissa);
    d = exponent < 0 ? d / kExactPowersOfTen[-exponent] : d * kExactPowersOfTen[exponent];
    if (d < std::numeric_limits<float>::min() || d > std::numeric_limits<float>::max()) return false;
    std::uint64_t bits = 0;
    std::memcpy(&bits, &d, sizeof bits);
    constexpr std::uint64_t kDroppedBits = (std::uint64_t{1} << 29) - 1;  // double -> float drops 29 bits
    if ((bits & kDroppedBits) == (std::uint64_t{1} << 28)) return false;  // exactly halfway
    out = static_cast<float>(negative ? -d : d);
    first = p;
    return true;
}

// Parses the whole token as a float, correctly rounded; "nan", "inf" and "infinity" are
// accepted, and values beyond the float range become +-Inf or 0. False if it is not a number.
bool parse_float(std::string_view token, float& out) {
    const char* p = token.data();
    if (scan_float_fast(p, token.data() + token.size(), out) && p == token.data() + token.size()) return true;
    token = without_plus(token);
    const char* first = token.data();
    const char* last = first + token.size();
    const auto [end, ec] = std::from_chars(first, last, out);
    if (ec == std::errc() && end == last) return true;
    if (ec != std::errc::result_out_of_range || end != last) return false;
    long double wide = 0;
    const auto [wide_end, wide_ec] = std::from_chars(first, last, wide);
    if (wide_ec != std::errc() || wide_end != last) return false;
    out = to_float(wide);
    return true;
}

// Parses the whole token as a signed 64-bit integer.
bool parse_int(std::string_view token, std::int64_t& out) {
    token = without_plus(token);
    const char* last = token.data() + token.size();
    const auto [end, ec] = std::from_chars(token.data(), last, out);
    return ec == std::errc() && end == last;
}

// Whether `token` is written as an integer (an optional sign and digits), whatever its size.
bool is_integer_text(std::string_view token) {
    if (!token.empty() && (token[0] == '+' || token[0] == '-')) token.remove_prefix(1);
    if (token.empty()) return false;
    for (char c : token)
        if (c < '0' || c > '9') return false;
    return true;
}

using CharSet = std::array<bool, 256>;

constexpr CharSet make_separators(bool comma) {
    CharSet set{};
    set[' '] = set['\t'] = set['\r'] = set['\f'] = set['\v'] = true;
    set[','] = comma;
    return set;
}
constexpr CharSet kBlanks = make_separators(false);
constexpr CharSet kFieldSeparators = make_separators(true);  // text point files: blanks and commas

bool is_blank(char c) { return kBlanks[static_cast<unsigned char>(c)]; }

// Splits the next token off `rest`, tokens being separated by characters of `separators`;
// empty when none is left.
std::string_view next_token(std::string_view& rest, const CharSet& separators = kBlanks) {
    const auto is_separator = [&](char c) { return separators[static_cast<unsigned char>(c)]; };
    std::size_t i = 0;
    while (i < rest.size() && is_separator(rest[i])) ++i;
    std::size_t j = i;
    while (j < rest.size() && !is_separator(rest[j])) ++j;
    const std::string_view token = rest.substr(i, j - i);
    rest.remove_prefix(j);
    return token;
}

// `line` up to its first '#'.
std::string_view without_comment(std::string_view line) {
    const void* hash = std::memchr(line.data(), '#', line.size());
    return hash ? line.substr(0, static_cast<std::size_t>(static_cast<const char*>(hash) - line.data()))
                : line;
}

bool is_blank_line(std::string_view line) { return std::all_of(line.begin(), line.end(), is_blank); }

// The OFF header keyword: OFF with optional ST, C, N prefixes (COFF, NOFF, CNOFF, STOFF...).
bool is_off_keyword(std::string_view token) {
    if (token.size() < 3 || token.substr(token.size() - 3) != "OFF") return false;
    const std::string_view prefix = token.substr(0, token.size() - 3);
    return prefix.find_first_not_of("STCN") == std::string_view::npos;
}

// ---------------------------------------------------------------------------------------------
// InputFile: a file read through one buffer, as lines (text) or as byte ranges (binary), with
// the position kept for messages.

class InputFile {
public:
    explicit InputFile(const std::string& path) : path_(path) {
        namespace fs = std::filesystem;
        std::error_code ec;
        const fs::file_status status = fs::status(path, ec);
        if (status.type() == fs::file_type::not_found) fail("cannot open: no such file");
        if (ec) fail("cannot open: " + ec.message());
        if (fs::is_directory(status)) fail("is a directory, not a file");
        if (!fs::is_regular_file(status)) fail("not a regular file");
        size_ = fs::file_size(path, ec);
        if (ec) fail("cannot determine the file size: " + ec.message());
        file_ = std::fopen(path.c_str(), "rb");
        if (!file_) fail(std::string("cannot open: ") + std::strerror(errno));
        // A buffer no larger than the file (plus one byte, to see its end): small files are
        // read without touching a whole megabyte of memory.
        buffer_.resize(static_cast<std::size_t>(std::min<std::uint64_t>(kBufferBytes, size_ + 1)));
    }
    ~InputFile() {
        if (file_) std::fclose(file_);
    }
    InputFile(const InputFile&) = delete;
    InputFile& operator=(const InputFile&) = delete;

    std::uint64_t size() const { return size_; }
    // File offset of the next unconsumed byte.
    std::uint64_t offset() const { return buffer_offset_ + pos_; }
    std::uint64_t remaining() const { return size_ > offset() ? size_ - offset() : 0; }
    std::uint64_t line_number() const { return line_; }

    const unsigned char* data() const {
        return reinterpret_cast<const unsigned char*>(buffer_.data()) + pos_;
    }
    std::size_t available() const { return end_ - pos_; }
    void consume(std::size_t n) {
        assert(n <= available());
        pos_ += n;
    }

    // Makes at least n bytes available unless the file ends first (n is capped at what the file
    // holds, so a corrupt count never allocates beyond the file size). Returns available().
    std::size_t fill(std::size_t n) {
        if (available() >= n) return available();
        n = static_cast<std::size_t>(std::min<std::uint64_t>(n, remaining()));
        if (available() >= n || eof_) return available();
        compact();
        if (buffer_.size() < n) buffer_.resize(n);
        while (end_ < n && !eof_) read_more();
        return available();
    }

    // Consumes up to n bytes; returns how many there were.
    std::uint64_t skip(std::uint64_t n) {
        std::uint64_t done = 0;
        while (done < n) {
            const auto want = static_cast<std::size_t>(std::min<std::uint64_t>(n - done, kBufferBytes));
            const std::size_t got = std::min(fill(want), want);
            if (got == 0) break;
            consume(got);
            done += got;
        }
        return done;
    }

    // Copies the next n bytes to dst, the buffered ones first and the rest with one fread.
    // Returns how many bytes were copied (fewer than n only at the end of the file).
    std::size_t read_into(void* dst, std::size_t n) {
        auto* out = static_cast<char*>(dst);
        const std::size_t from_buffer = std::min(n, available());
        if (from_buffer > 0) std::memcpy(out, buffer_.data() + pos_, from_buffer);
        pos_ += from_buffer;
        std::size_t copied = from_buffer;
        if (copied < n && !eof_) {
            const std::uint64_t at = offset();
            copied += std::fread(out + copied, 1, n - copied, file_);
            if (std::ferror(file_)) fail(std::string("read error: ") + std::strerror(errno));
            buffer_offset_ = at + (copied - from_buffer);
            pos_ = end_ = 0;
            if (copied < n) eof_ = true;
        }
        return copied;
    }

    // The next line without its line break (LF or CRLF); false at the end of the file.
    // The view stays valid until the next call.
    bool next_line(std::string_view& line) {
        for (;;) {
            const char* begin = buffer_.data() + pos_;
            const std::size_t avail = available();
            if (const void* nl = std::memchr(begin, '\n', avail)) {
                const auto len = static_cast<std::size_t>(static_cast<const char*>(nl) - begin);
                pos_ += len + 1;
                return emit_line(line, begin, len);
            }
            if (eof_) {
                if (avail == 0) return false;
                pos_ = end_;
                return emit_line(line, begin, avail);
            }
            if (avail >= kMaxLineBytes)
                fail_at_line(line_ + 1, "line longer than " + std::to_string(kMaxLineBytes >> 20) +
                                            " MiB (binary data in a text file?)");
            compact();
            // Room for the rest of the line (a file that grew after it was opened may need more
            // than its size at opening): the buffer grows up to kMaxLineBytes.
            if (end_ == buffer_.size()) buffer_.resize(std::min(2 * buffer_.size(), kMaxLineBytes));
            read_more();
        }
    }

    [[noreturn]] void fail(const std::string& what) const { throw IoError(path_ + ": " + what); }
    [[noreturn]] void fail_at_line(std::uint64_t line, const std::string& what) const {
        fail("line " + std::to_string(line) + ": " + what);
    }
    [[noreturn]] void fail_line(const std::string& what) const { fail_at_line(line_, what); }
    [[noreturn]] void fail_at_offset(std::uint64_t offset, const std::string& what) const {
        fail("byte offset " + std::to_string(offset) + ": " + what);
    }

private:
    bool emit_line(std::string_view& line, const char* begin, std::size_t len) {
        if (len > 0 && begin[len - 1] == '\r') --len;
        line = std::string_view(begin, len);
        ++line_;
        return true;
    }
    void compact() {
        if (pos_ == 0) return;
        std::memmove(buffer_.data(), buffer_.data() + pos_, end_ - pos_);
        buffer_offset_ += pos_;
        end_ -= pos_;
        pos_ = 0;
    }
    void read_more() {
        const std::size_t got = std::fread(buffer_.data() + end_, 1, buffer_.size() - end_, file_);
        end_ += got;
        if (std::ferror(file_)) fail(std::string("read error: ") + std::strerror(errno));
        if (got == 0 || std::feof(file_)) eof_ = true;
    }

    std::string path_;
    std::FILE* file_ = nullptr;
    std::uint64_t size_ = 0;
    std::vector<char> buffer_;
    std::size_t pos_ = 0;              // next unconsumed byte in buffer_
    std::size_t end_ = 0;              // end of the valid bytes in buffer_
    std::uint64_t buffer_offset_ = 0;  // file offset of buffer_[0]
    std::uint64_t line_ = 0;           // lines returned so far
    bool eof_ = false;
};

// Reports a token that should have been a number, or binary data if the line is not text.
[[noreturn]] void fail_not_number(const InputFile& in, std::string_view line, std::string_view token) {
    if (has_binary_byte(line)) in.fail_line("binary data, not text");
    in.fail_line(quote_token(token) + " is not a number");
}

float parse_coordinate(const InputFile& in, std::string_view line, std::string_view token) {
    float v = 0.0f;
    if (!parse_float(token, v)) fail_not_number(in, line, token);
    return v;
}

// Adds polygon corner lists to a FileGeometry.
void begin_faces(FileGeometry& g) {
    if (g.face_offsets.empty()) g.face_offsets.push_back(0);
}
void end_face(FileGeometry& g) { g.face_offsets.push_back(g.face_indices.size()); }

std::string count_text(std::uint64_t n, const std::string& what) { return std::to_string(n) + " " + what; }

// ---------------------------------------------------------------------------------------------
// PLY

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
        case PlyType::uint8: return 1;
        case PlyType::int16:
        case PlyType::uint16: return 2;
        case PlyType::int32:
        case PlyType::uint32:
        case PlyType::float32: return 4;
        case PlyType::float64: return 8;
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
        case PlyType::int8: return static_cast<float>(load<std::int8_t>(p, swap));
        case PlyType::uint8: return static_cast<float>(load<std::uint8_t>(p, swap));
        case PlyType::int16: return static_cast<float>(load<std::int16_t>(p, swap));
        case PlyType::uint16: return static_cast<float>(load<std::uint16_t>(p, swap));
        case PlyType::int32: return static_cast<float>(load<std::int32_t>(p, swap));
        case PlyType::uint32: return static_cast<float>(load<std::uint32_t>(p, swap));
        case PlyType::float32: return load<float>(p, swap);
        case PlyType::float64: return to_float(load<double>(p, swap));
    }
    return 0.0f;
}

// Precondition: is_integer(t).
std::int64_t load_integer(const unsigned char* p, PlyType t, bool swap) {
    switch (t) {
        case PlyType::int8: return load<std::int8_t>(p, swap);
        case PlyType::uint8: return load<std::uint8_t>(p, swap);
        case PlyType::int16: return load<std::int16_t>(p, swap);
        case PlyType::uint16: return load<std::uint16_t>(p, swap);
        case PlyType::int32: return load<std::int32_t>(p, swap);
        case PlyType::uint32: return load<std::uint32_t>(p, swap);
        case PlyType::float32:
        case PlyType::float64: break;
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
        case PlyEncoding::ascii: return "ascii";
        case PlyEncoding::binary_little_endian: return "binary_little_endian";
        case PlyEncoding::binary_big_endian: return "binary_big_endian";
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
            if (encoding == "ascii") h.encoding = PlyEncoding::ascii;
            else if (encoding == "binary_little_endian") h.encoding = PlyEncoding::binary_little_endian;
            else if (encoding == "binary_big_endian") h.encoding = PlyEncoding::binary_big_endian;
            else in.fail_line("unknown PLY format " + quote_token(encoding));
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
            if (h_.encoding == PlyEncoding::ascii) read_ascii_element(h_.elements[i], roles_[i]);
            else read_binary_element(h_.elements[i], roles_[i]);
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
                const auto faces =
                    static_cast<std::size_t>(std::min(e.count, in_.remaining() / min_face_bytes + 1));
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
            if (h_.encoding == PlyEncoding::ascii) bytes += 2;
            else bytes += type_size(p.is_list ? p.count_type : p.type);
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
                    in_.fail("the file ends after " + std::to_string(r) + " of " + std::to_string(e.count) +
                             " '" + e.name + "' records (line " + std::to_string(in_.line_number()) + ")");
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
                if (roles[j] == Role::x) p.x = v;
                else if (roles[j] == Role::y) p.y = v;
                else if (roles[j] == Role::z) p.z = v;
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
            fail("face " + std::to_string(face) + " has " + std::to_string(n) +
                 " corners; a face needs at least 3");
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
                                             " bytes) ends inside '" + e.name + "' record " +
                                             std::to_string(r) + " of " + std::to_string(e.count));
    }

    bool swap() const {
        return (h_.encoding == PlyEncoding::binary_little_endian) != host_is_little_endian();
    }

    void read_binary_element(const PlyElement& e, const std::vector<Role>& roles) {
        const bool fixed = std::none_of(e.properties.begin(), e.properties.end(),
                                        [](const PlyProperty& p) { return p.is_list; });
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
                                     offset[2] == 8 && type[0] == PlyType::float32 &&
                                     type[1] == PlyType::float32 && type[2] == PlyType::float32;
        if (exact_float_xyz) {
            const std::size_t start = out.size();
            out.resize(start + count);
            const std::size_t got = in_.read_into(out.data() + start, count * stride);
            if (got < count * stride) fail_truncated(e, got / stride);
            return;
        }
        const bool native_floats = !swap_bytes && type[0] == PlyType::float32 &&
                                   type[1] == PlyType::float32 && type[2] == PlyType::float32;
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
        const bool is_vertex = e.name == "vertex" &&
                               std::any_of(roles.begin(), roles.end(), [](Role r) { return r == Role::x; });
        if (is_vertex) out_.positions.reserve(static_cast<std::size_t>(e.count));
        for (std::uint64_t r = 0; r < e.count; ++r) {
            Vec3 p;
            for (std::size_t j = 0; j < e.properties.size(); ++j) {
                const PlyProperty& prop = e.properties[j];
                if (!prop.is_list) {
                    const std::size_t size = type_size(prop.type);
                    need(size, e, r);
                    if (roles[j] == Role::x) p.x = load_coordinate(in_.data(), prop.type, swap_bytes);
                    else if (roles[j] == Role::y) p.y = load_coordinate(in_.data(), prop.type, swap_bytes);
                    else if (roles[j] == Role::z) p.z = load_coordinate(in_.data(), prop.type, swap_bytes);
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

void read_ply(InputFile& in, ReadFaces faces, FileGeometry& g) {
    const PlyHeader h = read_ply_header(in);
    g.format = "ply";
    g.encoding = encoding_name(h.encoding);
    for (const PlyElement& e : h.elements) g.elements.push_back({e.name, e.count, e.declarations});
    PlyBodyReader(in, h, faces, g).read();
}

// ---------------------------------------------------------------------------------------------
// Text point files

void skip_byte_order_mark(InputFile& in) {
    if (in.fill(3) >= 3 && std::memcmp(in.data(), "\xEF\xBB\xBF", 3) == 0) in.consume(3);
}

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

// ---------------------------------------------------------------------------------------------
// OBJ

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
                        in.fail_line("vertex index " + std::string(v) + " is out of range (" +
                                     std::to_string(defined) + " vertices are defined above this line)");
                    in.fail_line("face corner " + quote_token(corner) +
                                 " does not start with a vertex index");
                }
                if (index == 0) in.fail_line("vertex index 0 (OBJ indices start at 1)");
                // Negative indices count back from the latest vertex: -1 is the last one defined.
                const std::int64_t resolved =
                    index > 0 ? index - 1 : static_cast<std::int64_t>(defined) + index;
                if (resolved < 0 || static_cast<std::uint64_t>(resolved) >= defined)
                    in.fail_line("vertex index " + std::to_string(index) + " is out of range (" +
                                 std::to_string(defined) + " vertices are defined above this line)");
                g.face_indices.push_back(static_cast<std::uint32_t>(resolved));
            }
            const std::size_t corners = g.face_indices.size() - first;
            if (corners < 3)
                in.fail_line("a face needs at least 3 corners, found " + std::to_string(corners));
            end_face(g);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// OFF

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

void read_off(InputFile& in, ReadFaces faces, FileGeometry& g) {
    g.format = "off";
    g.encoding = "text";
    skip_byte_order_mark(in);
    std::string_view line;
    if (!next_data_line(in, line)) in.fail("no OFF header");
    std::string_view rest = line;
    const std::string_view keyword = next_token(rest);
    if (!is_off_keyword(keyword))
        in.fail_line("not an OFF file (the header keyword is " + quote_token(keyword) + ")");
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
                in.fail_line("face " + std::to_string(f) + " has fewer than " + std::to_string(n) +
                             " indices");
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

// ---------------------------------------------------------------------------------------------
// Format choice

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
    if (head.size() >= 4 && head.substr(0, 3) == "ply" && (head[3] == '\n' || head[3] == '\r'))
        return Format::ply;
    const std::size_t keyword_end = head.find_first_of(" \t\r\n");
    if (keyword_end != std::string_view::npos && is_off_keyword(head.substr(0, keyword_end)))
        return Format::off;
    in.fail("unknown file format: " +
            (ext.empty() ? std::string("no extension") : "extension " + quote_token(ext)) +
            " is not one of .ply .xyz .txt .pts .csv .obj .off, and the content is not PLY or OFF");
}

}  // namespace

FileGeometry read_geometry(const std::string& path, ReadFaces faces) {
    InputFile in(path);
    if (in.size() == 0) in.fail("empty file");
    FileGeometry g;
    switch (choose_format(path, in)) {
        case Format::ply: read_ply(in, faces, g); break;
        case Format::xyz: read_xyz(in, false, g); break;
        case Format::pts: read_xyz(in, true, g); break;
        case Format::obj: read_obj(in, faces, g); break;
        case Format::off: read_off(in, faces, g); break;
    }
    if (faces == ReadFaces::yes && g.positions.size() > std::numeric_limits<std::uint32_t>::max())
        in.fail("too many vertices for 32-bit face indices (" + std::to_string(g.positions.size()) + ")");
    return g;
}

namespace {
bool is_finite(const Vec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }
}  // namespace

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
    FileGeometry g = read_geometry(path, ReadFaces::no);
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
    return info;
}

}  // namespace nmesh
