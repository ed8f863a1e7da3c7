// Helpers shared by the reader and writer tests.
#pragma once

#include <string>

#include "nmesh/error.h"

namespace nmesh::test {

// Runs read(path), which must throw IoError; checks that the message is one line starting with
// the path, and returns it.
template <class Read>
std::string io_error_of(const std::string& path, Read read) {
    try {
        read(path);
    } catch (const IoError& e) {
        const std::string message = e.what();
        CHECK_MESSAGE(message.rfind(path + ": ", 0) == 0, message);
        CHECK_MESSAGE(message.find('\n') == std::string::npos, message);
        return message;
    }
    FAIL("no IoError reading " << path);
    return "";
}

}  // namespace nmesh::test
