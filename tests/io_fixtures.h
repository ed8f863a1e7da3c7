// Helpers shared by the reader and writer tests.
#pragma once

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

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
        CHECK_MESSAGE(e.path() == path, message);  // the path alone, for a caller to use
        CHECK_MESSAGE(message.find('\n') == std::string::npos, message);
        return message;
    }
    FAIL("no IoError reading " << path);
    return "";
}

// A fresh directory, removed with its contents when the test ends.
struct TempDir {
    std::filesystem::path path;
    explicit TempDir(const std::string& prefix) {
        static int serial = 0;
        const auto stamp = std::chrono::steady_clock::now().time_since_epoch().count();
        path =
            std::filesystem::temp_directory_path() / (prefix + std::to_string(stamp) + "_" + std::to_string(serial++));
        std::filesystem::create_directories(path);
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;

    std::string at(const std::string& name) const { return (path / name).string(); }
    // Writes `bytes` to a file called `name` in the directory; returns its path.
    std::string file(const std::string& name, const std::string& bytes) const {
        std::ofstream out(at(name), std::ios::binary);
        out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
        REQUIRE(out.good());
        return at(name);
    }
    // The names in the directory, sorted.
    std::vector<std::string> names() const {
        std::vector<std::string> result;
        for (const auto& entry : std::filesystem::directory_iterator(path))
            result.push_back(entry.path().filename().string());
        std::sort(result.begin(), result.end());
        return result;
    }
};

}  // namespace nmesh::test
