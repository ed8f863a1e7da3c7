// nmesh/error.h — the exceptions nmesh throws at its boundary.
//
// Internal invariants are asserts; everything a caller can cause (a bad file, a bad parameter,
// a cloud too small to reconstruct) is one of these, with a message that names the problem and,
// for files, the file.
#pragma once

#include <stdexcept>
#include <string>

namespace nmesh {

// Base of every nmesh exception.
class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// A file could not be read or written, or its contents are malformed.
// The message starts with the path: "bunny.ply: truncated binary body (...)".
class IoError : public Error {
public:
    using Error::Error;
};

// The rule: ParameterError when an argument or parameter value is outside its documented range
// (the caller can fix the call); InputError when the data, a cloud or a mesh, cannot be
// processed, including a run that exceeds the library's capacity for it; IoError for files.

// A parameter is out of range; the message names the parameter.
class ParameterError : public Error {
public:
    using Error::Error;
};

// The input data cannot be reconstructed or processed (for example fewer than 4 distinct points,
// a non-finite coordinate, a mesh that refers to a vertex it does not have).
class InputError : public Error {
public:
    using Error::Error;
};

}  // namespace nmesh
