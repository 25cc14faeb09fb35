// The error every command reports: a message for the user, printed as
// "statmc: error: <message>" with exit code 1.
#pragma once

#include <stdexcept>
#include <string>

namespace statmc::host {

class HostError : public std::runtime_error {
public:
    explicit HostError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace statmc::host
