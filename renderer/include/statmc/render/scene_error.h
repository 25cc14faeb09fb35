// The one error type of scene reading (tokenizer, parser, camera).
#pragma once

#include <stdexcept>
#include <string>

namespace statmc::render {

/// A scene file problem that stops the render: "<file>:<line>: <what>".
class SceneError : public std::runtime_error {
public:
    explicit SceneError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace statmc::render
