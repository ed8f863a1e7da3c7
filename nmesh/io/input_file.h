// nmesh/io/input_file.h — a file read through one buffer, as lines or as byte ranges, with the
// position kept for error messages; and what every reader does with it.
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

#include "nmesh/error.h"
#include "nmesh/io.h"
#include "nmesh/io/text_scan.h"

namespace nmesh::io_detail {

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

    const unsigned char* data() const { return reinterpret_cast<const unsigned char*>(buffer_.data()) + pos_; }
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

    [[noreturn]] void fail(const std::string& what) const { throw IoError(path_, what); }
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
[[noreturn]] inline void fail_not_number(const InputFile& in, std::string_view line, std::string_view token) {
    if (has_binary_byte(line)) in.fail_line("binary data, not text");
    in.fail_line(quote_token(token) + " is not a number");
}

inline float parse_coordinate(const InputFile& in, std::string_view line, std::string_view token) {
    float v = 0.0f;
    if (!parse_float(token, v)) fail_not_number(in, line, token);
    return v;
}

// Adds polygon corner lists to a FileGeometry.
inline void begin_faces(FileGeometry& g) {
    if (g.face_offsets.empty()) g.face_offsets.push_back(0);
}
inline void end_face(FileGeometry& g) { g.face_offsets.push_back(g.face_indices.size()); }

// Skips a UTF-8 byte-order mark at the start of a text file.
inline void skip_byte_order_mark(InputFile& in) {
    if (in.fill(3) >= 3 && std::memcmp(in.data(), "\xEF\xBB\xBF", 3) == 0) in.consume(3);
}

inline std::string count_text(std::uint64_t n, const std::string& what) { return std::to_string(n) + " " + what; }

}  // namespace nmesh::io_detail
