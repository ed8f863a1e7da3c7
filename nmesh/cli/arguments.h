// nmesh/cli/arguments.h — a small command-line parser: positional arguments and --options.
#pragma once

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace nmesh::cli {

// A usage error: the CLI prints it with a hint and exits with status 2.
class UsageError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

class Arguments {
public:
    // `flags` are the options that take no value; `valued` those that take one ("-o" included).
    Arguments(int argc, char** argv, int first, const std::vector<std::string>& flags,
              const std::vector<std::string>& valued);

    const std::vector<std::string>& positional() const { return positional_; }
    bool has(const std::string& name) const { return values_.count(name) != 0; }
    std::string text(const std::string& name, const std::string& fallback = "") const;
    double number(const std::string& name, double fallback) const;
    std::uint64_t count(const std::string& name, std::uint64_t fallback) const;
    std::vector<std::uint64_t> count_list(const std::string& name) const;

private:
    std::vector<std::string> positional_;
    std::map<std::string, std::string> values_;
};

}  // namespace nmesh::cli
