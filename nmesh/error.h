// nmesh/error.h — the exceptions nmesh throws at its boundary.
//
// Internal invariants are asserts; everything a caller can cause (a bad file, a bad parameter,
// a cloud too small to reconstruct) is one of these, with a message that names the problem and,
// for files, the file. An IoError also carries its path and a ParameterError its parameter's
// name, so that a caller can tell which without reading the message.
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
    // `path`: the file; `problem`: what is wrong. The message is "path: problem" ("(empty path):
    // problem" for an empty path).
    IoError(const std::string& path, const std::string& problem)
        : Error((path.empty() ? std::string("(empty path)") : path) + ": " + problem), path_(path) {}
    // The file's path, as the caller gave it.
    const std::string& path() const noexcept { return path_; }

private:
    std::string path_;
};

// The rule: ParameterError when an argument or parameter value is outside its documented range
// (the caller can fix the call); InputError when the data, a cloud or a mesh, cannot be
// processed, including a run that exceeds the library's capacity for it; IoError for files.

// A parameter is out of range; the message names the parameter.
class ParameterError : public Error {
public:
    // `parameter`: the parameter's name as the caller spells it (a field of Parameters or of an
    // options struct, or a function's argument); `message`: the whole message, which names it.
    ParameterError(const std::string& parameter, const std::string& message) : Error(message), parameter_(parameter) {}
    // The name of the parameter out of range.
    const std::string& parameter() const noexcept { return parameter_; }

private:
    std::string parameter_;
};

// The input data cannot be reconstructed or processed (for example fewer than 4 distinct points,
// a non-finite coordinate, a mesh that refers to a vertex it does not have).
class InputError : public Error {
public:
    using Error::Error;
};

}  // namespace nmesh
