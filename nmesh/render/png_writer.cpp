// nmesh/png_writer.cpp — PNG chunks, row filters, and a fixed-Huffman deflate with LZ77.
#include "nmesh/render/png_writer.h"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <limits>
#include <ostream>

#include "nmesh/error.h"
#include "nmesh/io.h"

namespace nmesh {
namespace {

// ---- checksums ----------------------------------------------------------------------------------

constexpr std::array<std::uint32_t, 256> make_crc_table() {
    std::array<std::uint32_t, 256> table{};
    for (std::uint32_t n = 0; n < 256; ++n) {
        std::uint32_t c = n;
        for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
        table[n] = c;
    }
    return table;
}
constexpr std::array<std::uint32_t, 256> kCrcTable = make_crc_table();

// ---- deflate (RFC 1951) -------------------------------------------------------------------------

// Largest back-reference distance deflate allows.
constexpr std::size_t kWindow = 32768;
// Match lengths deflate can express.
constexpr std::size_t kMinMatch = 3, kMaxMatch = 258;
// Largest stored block, and the input span of every block (so any block may fall back to stored).
constexpr std::size_t kBlockSize = 65535;
// Candidates examined per position: more finds slightly longer matches on busy images, at a cost
// proportional to it; 32 keeps rendered images within a few percent of unbounded search.
constexpr int kMaxChain = 32;
// Hash table of 3-byte prefixes: 2^15 heads (128 KiB), enough for a 32 KiB window.
constexpr int kHashBits = 15;

// Length codes 257..285: the smallest length of each and its number of extra bits.
constexpr std::uint16_t kLengthBase[29] = {3,  4,  5,  6,  7,  8,  9,  10, 11,  13,  15,  17,  19,  23, 27,
                                           31, 35, 43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258};
constexpr std::uint8_t kLengthExtra[29] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2,
                                           2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
// Distance codes 0..29: the smallest distance of each and its number of extra bits.
constexpr std::uint16_t kDistBase[30] = {1,    2,    3,    4,    5,    7,    9,    13,    17,    25,
                                         33,   49,   65,   97,   129,  193,  257,  385,   513,   769,
                                         1025, 1537, 2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577};
constexpr std::uint8_t kDistExtra[30] = {0, 0, 0, 0, 1, 1, 2, 2,  3,  3,  4,  4,  5,  5,  6,
                                         6, 7, 7, 8, 8, 9, 9, 10, 10, 11, 11, 12, 12, 13, 13};

std::uint32_t reverse_bits(std::uint32_t code, int length) {
    std::uint32_t r = 0;
    for (int i = 0; i < length; ++i) r |= ((code >> i) & 1u) << (length - 1 - i);
    return r;
}

// A Huffman code as written: its bits already reversed (deflate sends codes most significant bit
// first into a least-significant-bit-first stream), and its length.
struct Code {
    std::uint16_t bits = 0;
    std::uint8_t length = 0;
};

// The fixed literal/length code of RFC 1951 section 3.2.6.
struct FixedCodes {
    std::array<Code, 288> literal{};
    std::array<Code, 30> distance{};
    FixedCodes() {
        for (std::uint32_t s = 0; s < 288; ++s) {
            std::uint32_t code = 0;
            int length = 0;
            if (s < 144)
                code = 0x30 + s, length = 8;
            else if (s < 256)
                code = 0x190 + (s - 144), length = 9;
            else if (s < 280)
                code = s - 256, length = 7;
            else
                code = 0xC0 + (s - 280), length = 8;
            literal[s] = {std::uint16_t(reverse_bits(code, length)), std::uint8_t(length)};
        }
        for (std::uint32_t d = 0; d < 30; ++d) distance[d] = {std::uint16_t(reverse_bits(d, 5)), 5};
    }
};
const FixedCodes& fixed_codes() {
    static const FixedCodes codes;
    return codes;
}

// Which code a match length or distance takes, by table: lengths directly, distances up to 256
// directly and larger ones by (distance - 1) >> 7, as the codes above 256 span multiples of 128.
struct SymbolTables {
    std::array<std::uint8_t, kMaxMatch + 1> length{};
    std::array<std::uint8_t, 512> distance{};
    SymbolTables() {
        for (std::size_t len = kMinMatch; len <= kMaxMatch; ++len)
            length[len] = std::uint8_t(std::upper_bound(std::begin(kLengthBase), std::end(kLengthBase), len) -
                                       std::begin(kLengthBase) - 1);
        const auto code_of = [](std::size_t d) {
            return std::uint8_t(std::upper_bound(std::begin(kDistBase), std::end(kDistBase), d) -
                                std::begin(kDistBase) - 1);
        };
        for (std::size_t d = 1; d <= 256; ++d) distance[d - 1] = code_of(d);
        for (std::size_t k = 2; k < 256; ++k) distance[256 + k] = code_of((k << 7) + 1);
    }
};
const SymbolTables& symbol_tables() {
    static const SymbolTables tables;
    return tables;
}
// Index of the length code for a match length in [3, 258], and of the distance code for a
// distance in [1, 32768].
int length_symbol(std::size_t length) { return symbol_tables().length[length]; }
int distance_symbol(std::size_t distance) {
    return distance <= 256 ? symbol_tables().distance[distance - 1]
                           : symbol_tables().distance[256 + ((distance - 1) >> 7)];
}

// Appends bits to a byte vector, least significant bit first.
class BitWriter {
public:
    explicit BitWriter(std::vector<std::uint8_t>& out) : out_(out) {}
    void put(std::uint32_t bits, int count) {
        buffer_ |= std::uint64_t(bits) << used_;
        used_ += count;
        while (used_ >= 8) {
            out_.push_back(std::uint8_t(buffer_));
            buffer_ >>= 8;
            used_ -= 8;
        }
    }
    void put(const Code& c) { put(c.bits, c.length); }
    // Pads with zero bits to the next byte boundary.
    void align() {
        if (used_ > 0) put(0, 8 - used_);
    }

private:
    std::vector<std::uint8_t>& out_;
    std::uint64_t buffer_ = 0;
    int used_ = 0;
};

// One LZ77 token: a literal byte (distance 0) or a back-reference.
struct Token {
    std::uint16_t length_or_literal;
    std::uint16_t distance;
};

// Greedy LZ77 over a whole buffer, block by block, each block coded fixed or stored.
class Deflater {
public:
    Deflater(const std::vector<std::uint8_t>& data, std::vector<std::uint8_t>& out)
        : data_(data), bits_(out), head_(std::size_t(1) << kHashBits, -1), prev_(kWindow, -1) {}

    void run() {
        const std::size_t n = data_.size();
        std::size_t start = 0;
        do {
            const std::size_t end = std::min(n, start + kBlockSize);
            tokenize(start, end);
            emit_block(start, end, end == n);
            start = end;
        } while (start < n);
        bits_.align();
    }

private:
    std::uint32_t hash(std::size_t i) const {
        const std::uint32_t v =
            std::uint32_t(data_[i]) | std::uint32_t(data_[i + 1]) << 8 | std::uint32_t(data_[i + 2]) << 16;
        return (v * 2654435761u) >> (32 - kHashBits);
    }
    // Records position i (which needs 3 bytes after it) as the newest with its prefix.
    void insert(std::size_t i) {
        if (i + kMinMatch > data_.size()) return;
        const std::uint32_t h = hash(i);
        prev_[i % kWindow] = head_[h];
        head_[h] = std::int64_t(i);
    }

    // The tokens of data_[start, end): at each position the longest match among the newest
    // kMaxChain earlier positions with the same prefix hash, else a literal. Matches stop at
    // `end`, so each block decodes on its own given the window.
    void tokenize(std::size_t start, std::size_t end) {
        tokens_.clear();
        fixed_bits_ = 0;
        const FixedCodes& codes = fixed_codes();
        std::size_t i = start;
        while (i < end) {
            std::size_t best_len = 0, best_dist = 0;
            if (i + kMinMatch <= end) {
                const std::size_t limit = std::min(kMaxMatch, end - i);
                std::int64_t cand = head_[hash(i)];
                for (int chain = 0; chain < kMaxChain && cand >= 0; ++chain) {
                    const std::size_t c = std::size_t(cand);
                    const std::size_t dist = i - c;
                    if (dist > kWindow) break;
                    std::size_t len = 0;
                    while (len < limit && data_[c + len] == data_[i + len]) ++len;
                    if (len > best_len) {
                        best_len = len;
                        best_dist = dist;
                        if (len == limit) break;
                    }
                    const std::int64_t next = prev_[c % kWindow];
                    if (next >= cand) break;  // the slot was reused by a newer position
                    cand = next;
                }
            }
            if (best_len >= kMinMatch) {
                const int ls = length_symbol(best_len), ds = distance_symbol(best_dist);
                fixed_bits_ += codes.literal[257 + ls].length + kLengthExtra[ls] + 5 + kDistExtra[ds];
                tokens_.push_back({std::uint16_t(best_len), std::uint16_t(best_dist)});
                for (std::size_t k = 0; k < best_len; ++k) insert(i + k);
                i += best_len;
            } else {
                fixed_bits_ += codes.literal[data_[i]].length;
                tokens_.push_back({data_[i], 0});
                insert(i);
                ++i;
            }
        }
    }

    // Writes data_[start, end) as one block, fixed-Huffman or stored, whichever is smaller.
    void emit_block(std::size_t start, std::size_t end, bool last) {
        const FixedCodes& codes = fixed_codes();
        const std::size_t fixed_total = 3 + fixed_bits_ + codes.literal[256].length;
        const std::size_t stored_total = 3 + 7 + 32 + 8 * (end - start);  // worst-case alignment
        bits_.put(last ? 1 : 0, 1);
        if (stored_total < fixed_total) {
            bits_.put(0, 2);  // BTYPE 00: stored
            bits_.align();
            const std::uint32_t len = std::uint32_t(end - start);
            bits_.put(len & 0xFFFFu, 16);
            bits_.put(~len & 0xFFFFu, 16);
            for (std::size_t k = start; k < end; ++k) bits_.put(data_[k], 8);
            return;
        }
        bits_.put(1, 2);  // BTYPE 01: fixed Huffman codes
        for (const Token& t : tokens_) {
            if (t.distance == 0) {
                bits_.put(codes.literal[t.length_or_literal]);
                continue;
            }
            const int ls = length_symbol(t.length_or_literal), ds = distance_symbol(t.distance);
            bits_.put(codes.literal[257 + ls]);
            bits_.put(t.length_or_literal - kLengthBase[ls], kLengthExtra[ls]);
            bits_.put(codes.distance[ds]);
            bits_.put(t.distance - kDistBase[ds], kDistExtra[ds]);
        }
        bits_.put(codes.literal[256]);  // end of block
    }

    const std::vector<std::uint8_t>& data_;
    BitWriter bits_;
    std::vector<std::int64_t> head_;  // newest position per prefix hash, or -1
    std::vector<std::int64_t> prev_;  // per position modulo the window: the previous one with its hash
    std::vector<Token> tokens_;
    std::size_t fixed_bits_ = 0;
};

// ---- PNG ----------------------------------------------------------------------------------------

// The filter predictor of PNG filter type 4 (Paeth).
std::uint8_t paeth(int a, int b, int c) {
    const int p = a + b - c;
    const int pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
    if (pa <= pb && pa <= pc) return std::uint8_t(a);
    return std::uint8_t(pb <= pc ? b : c);
}

// The image's rows, each as its filter type byte followed by the filtered bytes, the filter chosen
// per row to minimise the sum of the filtered bytes' magnitudes taken as signed.
std::vector<std::uint8_t> filter_rows(int width, int height, const std::vector<std::uint8_t>& rgb) {
    constexpr std::size_t bpp = 3;
    const std::size_t stride = std::size_t(width) * bpp;
    std::vector<std::uint8_t> out;
    out.reserve((stride + 1) * std::size_t(height));
    const std::vector<std::uint8_t> zeros(stride, 0);
    std::array<std::vector<std::uint8_t>, 5> candidate;
    for (auto& c : candidate) c.resize(stride);
    for (std::size_t y = 0; y < std::size_t(height); ++y) {
        const std::uint8_t* row = rgb.data() + y * stride;
        const std::uint8_t* up = y > 0 ? row - stride : zeros.data();
        for (std::size_t i = 0; i < stride; ++i) {
            const int a = i >= bpp ? row[i - bpp] : 0;
            const int b = up[i];
            const int c = i >= bpp ? up[i - bpp] : 0;
            candidate[0][i] = row[i];
            candidate[1][i] = std::uint8_t(row[i] - a);
            candidate[2][i] = std::uint8_t(row[i] - b);
            candidate[3][i] = std::uint8_t(row[i] - ((a + b) >> 1));
            candidate[4][i] = std::uint8_t(row[i] - paeth(a, b, c));
        }
        int best = 0;
        std::uint64_t best_cost = std::numeric_limits<std::uint64_t>::max();
        for (int f = 0; f < 5; ++f) {
            std::uint64_t cost = 0;
            for (std::uint8_t v : candidate[f]) cost += std::uint64_t(std::abs(int(std::int8_t(v))));
            if (cost < best_cost) best_cost = cost, best = f;
        }
        out.push_back(std::uint8_t(best));
        out.insert(out.end(), candidate[best].begin(), candidate[best].end());
    }
    return out;
}

void put_u32(std::vector<std::uint8_t>& out, std::uint32_t v) {
    for (int shift = 24; shift >= 0; shift -= 8) out.push_back(std::uint8_t(v >> shift));
}

// Appends a chunk: length, type, data, and the CRC-32 of type and data.
void put_chunk(std::vector<std::uint8_t>& out, const char type[4], const std::uint8_t* data, std::size_t size) {
    put_u32(out, std::uint32_t(size));
    const std::size_t type_at = out.size();
    out.insert(out.end(), type, type + 4);
    out.insert(out.end(), data, data + size);
    put_u32(out, crc32(out.data() + type_at, size + 4));
}

// IDAT chunks hold at most this many bytes of the zlib stream. Any size up to 2^31 - 1 is valid;
// a fixed bound keeps every chunk length legal whatever the image size.
constexpr std::size_t kMaxIdat = std::size_t(1) << 20;

}  // namespace

std::uint32_t crc32(const std::uint8_t* data, std::size_t size, std::uint32_t previous) {
    std::uint32_t c = previous ^ 0xFFFFFFFFu;
    for (std::size_t i = 0; i < size; ++i) c = kCrcTable[(c ^ data[i]) & 0xFFu] ^ (c >> 8);
    return c ^ 0xFFFFFFFFu;
}

std::uint32_t adler32(const std::uint8_t* data, std::size_t size, std::uint32_t previous) {
    constexpr std::uint32_t kMod = 65521;  // the largest prime below 2^16
    // 5552 bytes is the longest run after which the sums cannot yet overflow 32 bits (RFC 1950).
    constexpr std::size_t kRun = 5552;
    std::uint32_t a = previous & 0xFFFFu, b = previous >> 16;
    while (size > 0) {
        const std::size_t run = std::min(size, kRun);
        for (std::size_t i = 0; i < run; ++i) {
            a += data[i];
            b += a;
        }
        a %= kMod;
        b %= kMod;
        data += run;
        size -= run;
    }
    return b << 16 | a;
}

std::vector<std::uint8_t> zlib_compress(const std::vector<std::uint8_t>& data) {
    std::vector<std::uint8_t> out;
    out.reserve(data.size() / 8 + 64);
    // CMF 0x78: deflate with a 32 KiB window; FLG 0x01: no dictionary, "fastest" level tag, and
    // (0x78 * 256 + 0x01) is a multiple of 31 as the header check requires.
    out.push_back(0x78);
    out.push_back(0x01);
    Deflater deflater(data, out);
    deflater.run();
    const std::uint32_t a = adler32(data.data(), data.size());
    for (int shift = 24; shift >= 0; shift -= 8) out.push_back(std::uint8_t(a >> shift));
    return out;
}

std::vector<std::uint8_t> encode_png(int width, int height, const std::vector<std::uint8_t>& rgb) {
    if (width < 1 || height < 1)
        throw ParameterError(width < 1 ? "width" : "height", "png: the image size must be at least 1x1, got " + std::to_string(width) + "x" +
                             std::to_string(height));
    const std::uint64_t expected = 3ull * std::uint64_t(width) * std::uint64_t(height);
    if (rgb.size() != expected)
        throw ParameterError("rgb", "png: a " + std::to_string(width) + "x" + std::to_string(height) + " RGB image needs " +
                             std::to_string(expected) + " bytes, got " + std::to_string(rgb.size()));

    std::vector<std::uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    std::vector<std::uint8_t> header;
    put_u32(header, std::uint32_t(width));
    put_u32(header, std::uint32_t(height));
    // Bit depth 8, colour type 2 (RGB), compression 0 (deflate), filter method 0, no interlace.
    header.insert(header.end(), {8, 2, 0, 0, 0});
    put_chunk(png, "IHDR", header.data(), header.size());

    const std::vector<std::uint8_t> stream = zlib_compress(filter_rows(width, height, rgb));
    for (std::size_t at = 0; at < stream.size(); at += kMaxIdat)
        put_chunk(png, "IDAT", stream.data() + at, std::min(kMaxIdat, stream.size() - at));
    put_chunk(png, "IEND", nullptr, 0);
    return png;
}

void write_png(const std::string& path, int width, int height, const std::vector<std::uint8_t>& rgb) {
    const std::vector<std::uint8_t> png = encode_png(width, height, rgb);
    write_file_atomically(path, [&](std::ostream& out) {
        out.write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
    });
}

}  // namespace nmesh
