#include "nmesh/cli/arguments.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>

namespace nmesh::cli {

Arguments::Arguments(int argc, char** argv, int first, const std::vector<std::string>& flags,
                     const std::vector<std::string>& valued) {
    auto known = [](const std::vector<std::string>& list, const std::string& s) {
        return std::find(list.begin(), list.end(), s) != list.end();
    };
    bool options_done = false;
    for (int i = first; i < argc; ++i) {
        std::string arg = argv[i];
        if (options_done || arg.size() < 2 || arg[0] != '-' || (arg[1] != '-' && arg != "-o" && arg != "-h")) {
            positional_.push_back(arg);
            continue;
        }
        if (arg == "--") {
            options_done = true;
            continue;
        }
        std::string value;
        bool has_value = false;
        if (const auto eq = arg.find('='); eq != std::string::npos) {
            value = arg.substr(eq + 1);
            arg = arg.substr(0, eq);
            has_value = true;
        }
        if (known(flags, arg)) {
            if (has_value) throw UsageError("option " + arg + " takes no value");
            values_[arg] = "";
        } else if (known(valued, arg)) {
            if (!has_value) {
                if (i + 1 >= argc) throw UsageError("option " + arg + " needs a value");
                value = argv[++i];
            }
            values_[arg] = value;
        } else {
            throw UsageError("unknown option " + arg);
        }
    }
}

std::string Arguments::text(const std::string& name, const std::string& fallback) const {
    const auto it = values_.find(name);
    return it == values_.end() ? fallback : it->second;
}

double Arguments::number(const std::string& name, double fallback) const {
    const auto it = values_.find(name);
    if (it == values_.end()) return fallback;
    const std::string& s = it->second;
    char* end = nullptr;
    const double v = std::strtod(s.c_str(), &end);
    if (s.empty() || *end != '\0' || !std::isfinite(v))
        throw UsageError("option " + name + " needs a number, got '" + s + "'");
    return v;
}

namespace {
std::uint64_t parse_count(const std::string& name, const std::string& s) {
    std::uint64_t v = 0;
    const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (s.empty() || ec != std::errc() || ptr != s.data() + s.size())
        throw UsageError("option " + name + " needs a whole number, got '" + s + "'");
    return v;
}
}  // namespace

std::uint64_t Arguments::count(const std::string& name, std::uint64_t fallback) const {
    const auto it = values_.find(name);
    return it == values_.end() ? fallback : parse_count(name, it->second);
}

std::vector<std::uint64_t> Arguments::count_list(const std::string& name) const {
    std::vector<std::uint64_t> out;
    const auto it = values_.find(name);
    if (it == values_.end()) return out;
    const std::string& s = it->second;
    std::size_t start = 0;
    while (start <= s.size()) {
        const std::size_t comma = std::min(s.find(',', start), s.size());
        out.push_back(parse_count(name, s.substr(start, comma - start)));
        start = comma + 1;
    }
    return out;
}

}  // namespace nmesh::cli
