// nmesh/io/text_scan.h — the small pieces the readers share: number parsing (correctly rounded
// decimal to float), tokens and separators, saturating counts, and quoting for messages.
#pragma once

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

#include "nmesh/io.h"

namespace nmesh::io_detail {

static_assert(sizeof(Vec3) == 12 && std::is_trivially_copyable_v<Vec3>,
              "the binary PLY fast path reads float x, y, z records straight into Vec3s");

// Read granularity: large enough that the per-call cost of fread vanishes, small enough to stay
// in cache while a chunk is converted.
inline constexpr std::size_t kBufferBytes = std::size_t{1} << 20;

// Longest accepted text line. No real point, vertex or face line comes near it; a longer "line"
// means binary data or a file without line breaks.
inline constexpr std::size_t kMaxLineBytes = kBufferBytes;

// ---------------------------------------------------------------------------------------------
// Small helpers

inline std::uint64_t saturating_add(std::uint64_t a, std::uint64_t b) {
    return a > std::numeric_limits<std::uint64_t>::max() - b ? std::numeric_limits<std::uint64_t>::max() : a + b;
}

inline std::uint64_t saturating_mul(std::uint64_t a, std::uint64_t b) {
    return (a != 0 && b > std::numeric_limits<std::uint64_t>::max() / a) ? std::numeric_limits<std::uint64_t>::max()
                                                                         : a * b;
}

inline bool host_is_little_endian() {
    const std::uint16_t one = 1;
    unsigned char first = 0;
    std::memcpy(&first, &one, 1);
    return first == 1;
}

// A token as it can be shown inside a one-line message: quoted, non-printable bytes escaped,
// long tokens shortened.
inline std::string quote_token(std::string_view token) {
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
inline bool has_binary_byte(std::string_view line) {
    for (char ch : line) {
        const auto c = static_cast<unsigned char>(ch);
        if ((c < 0x20 && c != '\t' && c != '\r' && c != '\f' && c != '\v') || c == 0x7f) return true;
    }
    return false;
}

inline float to_float(long double v) {
    if (v > std::numeric_limits<float>::max()) return std::numeric_limits<float>::infinity();
    if (v < -std::numeric_limits<float>::max()) return -std::numeric_limits<float>::infinity();
    return static_cast<float>(v);
}

inline std::string_view without_plus(std::string_view t) {
    if (t.size() > 1 && t[0] == '+' && t[1] != '+' && t[1] != '-') t.remove_prefix(1);
    return t;
}

inline bool is_digit(char c) { return c >= '0' && c <= '9'; }

// Powers of ten a double holds exactly (5^22 < 2^53).
inline constexpr double kExactPowersOfTen[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                               1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

// Clinger's fast path, several times faster than std::from_chars<float> here. A decimal whose
// digits form an integer m <= 2^53 and whose decimal exponent is within +-22 becomes a double with
// one correctly rounded operation (m and 10^|e| are exact); rounding that double to float is then
// correct unless it lies exactly halfway between two floats (checked), because no such halfway
// point can lie strictly between a value and its nearest double. False when the path does not
// apply (the caller falls back to std::from_chars), including non-numbers, subnormal and
// out-of-range results. On success `first` is moved past the number.
inline bool scan_float_fast(const char*& first, const char* const end, float& out) {
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
inline bool parse_float(std::string_view token, float& out) {
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
inline bool parse_int(std::string_view token, std::int64_t& out) {
    token = without_plus(token);
    const char* last = token.data() + token.size();
    const auto [end, ec] = std::from_chars(token.data(), last, out);
    return ec == std::errc() && end == last;
}

// Whether `token` is written as an integer (an optional sign and digits), whatever its size.
inline bool is_integer_text(std::string_view token) {
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
inline constexpr CharSet kBlanks = make_separators(false);
inline constexpr CharSet kFieldSeparators = make_separators(true);  // text point files: blanks and commas

inline bool is_blank(char c) { return kBlanks[static_cast<unsigned char>(c)]; }

// Splits the next token off `rest`, tokens being separated by characters of `separators`;
// empty when none is left.
inline std::string_view next_token(std::string_view& rest, const CharSet& separators = kBlanks) {
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
inline std::string_view without_comment(std::string_view line) {
    const void* hash = std::memchr(line.data(), '#', line.size());
    return hash ? line.substr(0, static_cast<std::size_t>(static_cast<const char*>(hash) - line.data())) : line;
}

inline bool is_blank_line(std::string_view line) { return std::all_of(line.begin(), line.end(), is_blank); }

// The OFF header keyword: OFF with optional ST, C, N prefixes (COFF, NOFF, CNOFF, STOFF...).
inline bool is_off_keyword(std::string_view token) {
    if (token.size() < 3 || token.substr(token.size() - 3) != "OFF") return false;
    const std::string_view prefix = token.substr(0, token.size() - 3);
    return prefix.find_first_not_of("STCN") == std::string_view::npos;
}

}  // namespace nmesh::io_detail
