// bench/number_list.h — the sweeps' lists of seeds, sizes and fractions: "1-10", "2,6", "1,3-5".
#pragma once

#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

namespace nmesh::bench {

// The numbers a comma-separated list of numbers and inclusive ranges names, in its order.
// std::invalid_argument (std::stoull's) when an item is not a number.
inline std::vector<std::uint64_t> parse_range(const std::string& text) {
    std::vector<std::uint64_t> out;
    std::stringstream in(text);
    for (std::string part; std::getline(in, part, ',');) {
        const auto dash = part.find('-');
        if (dash == std::string::npos) {
            out.push_back(std::stoull(part));
        } else {
            for (std::uint64_t s = std::stoull(part.substr(0, dash)); s <= std::stoull(part.substr(dash + 1)); ++s)
                out.push_back(s);
        }
    }
    return out;
}

}  // namespace nmesh::bench
