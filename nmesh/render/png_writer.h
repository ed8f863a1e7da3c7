// nmesh/png_writer.h — a small self-contained PNG encoder for 8-bit RGB images.
//
// The file is a standard PNG (signature, IHDR, IDAT chunks, IEND) that any viewer opens: 8 bits
// per channel, colour type 2 (RGB), no interlacing. Everything is computed here — the zlib stream,
// the CRC-32 of every chunk, the Adler-32 of the stream — so nmesh needs no zlib or libpng.
//
// Compression, chosen for images of rendered meshes (large areas of background, smooth shading):
//   - each row is filtered with whichever PNG filter (None, Sub, Up, Average, Paeth) gives the
//     smallest sum of absolute values of its output bytes taken as signed — the heuristic the PNG
//     specification recommends (section 12.8). Smooth shading filters to small numbers and
//     background to zeros;
//   - the filtered bytes are compressed with deflate using the fixed Huffman codes and greedy
//     LZ77 matching (hash chains over 3-byte prefixes, a 32 KiB window, at most 32 candidates per
//     position). Long runs become a few bits per 258 bytes. Dynamic Huffman codes
//     would shrink files by another 10-30% for two hundred more lines: not worth it for previews;
//   - every block of up to 65,535 input bytes is written "stored" (uncompressed) instead whenever
//     that is smaller, so incompressible images (noise) grow by at most 5 bytes per block.
// Measured on 1024x1024 renders of a 60,000-triangle mesh: the shaded image compresses to 10% of
// its 3 MiB of pixels, the wireframe to 24%; zlib's default level would make the files about 20%
// smaller.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace nmesh {

// The PNG file of an image: `rgb` holds width * height pixels of 3 bytes (red, green, blue), rows
// from top to bottom, each from left to right.
// Throws ParameterError if width or height is below 1 or above 2^31 - 1 (the PNG limit), or if
// rgb.size() != 3 * width * height.
// Cost: O(width * height); about 65 ms for a 1024x1024 render.
std::vector<std::uint8_t> encode_png(int width, int height, const std::vector<std::uint8_t>& rgb);

// Writes encode_png(width, height, rgb) to `path` through write_file_atomically: the file is
// either replaced by the complete image or left untouched. Throws what encode_png throws (before
// anything is created) and IoError for file errors.
void write_png(const std::string& path, int width, int height, const std::vector<std::uint8_t>& rgb);

// The zlib stream (RFC 1950) of `data` that encode_png stores in the IDAT chunks: the deflate
// blocks described above and the Adler-32 of `data`. Decodable by any inflate (zlib's
// uncompress(), Python's zlib.decompress). O(data.size()).
std::vector<std::uint8_t> zlib_compress(const std::vector<std::uint8_t>& data);

// The CRC-32 of ISO 3309 / ITU-T V.42 (polynomial 0xEDB88320 reflected), as PNG chunks and zlib's
// crc32() use it. `previous` chains calls: crc32(b, nb, crc32(a, na)) is the CRC of a then b.
// crc32 of "123456789" is 0xCBF43926.
std::uint32_t crc32(const std::uint8_t* data, std::size_t size, std::uint32_t previous = 0);

// The Adler-32 checksum of RFC 1950, which ends a zlib stream. `previous` chains calls as for
// crc32 (the checksum of nothing is 1). adler32 of "Wikipedia" is 0x11E60398.
std::uint32_t adler32(const std::uint8_t* data, std::size_t size, std::uint32_t previous = 1);

}  // namespace nmesh
