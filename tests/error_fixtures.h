// What a refusal names: the parameter of a ParameterError, the path of an IoError.
#pragma once

#include <string>

#include "nmesh/error.h"

namespace nmesh::test {

// ParameterError::parameter() of what `call` throws; "(nothing thrown)" when it throws nothing.
template <class Call>
std::string refused_parameter(Call call) {
    try {
        call();
    } catch (const ParameterError& e) {
        return e.parameter();
    }
    return "(nothing thrown)";
}

// IoError::path() of what `call` throws; "(nothing thrown)" when it throws nothing.
template <class Call>
std::string refused_path(Call call) {
    try {
        call();
    } catch (const IoError& e) {
        return e.path();
    }
    return "(nothing thrown)";
}

}  // namespace nmesh::test
