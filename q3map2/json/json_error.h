#pragma once

#include <stdexcept>

namespace q3::json {

// One line: "<file>:<line>:<column>: <record>: <what is wrong>".
struct JsonError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

}  // namespace q3::json
