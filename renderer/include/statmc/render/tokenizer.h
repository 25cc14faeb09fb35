// pbrt's lexical level: identifiers, quoted strings, numbers, brackets and # comments,
// each token remembering the line it came from so that every message can name file:line.
#pragma once

#include <string>
#include <vector>

#include "statmc/render/scene_error.h"

namespace statmc::render {

struct Token {
    enum class Kind { Identifier, String, Number, OpenBracket, CloseBracket };
    Kind kind;
    std::string text;  ///< the string without quotes, or the identifier / number text
    double number = 0;
    int line = 0;
};

/// Splits `text` (the contents of `file`) into tokens. Throws SceneError on an
/// unterminated string or a character pbrt does not know.
std::vector<Token> tokenize(const std::string& text, const std::string& file);

}  // namespace statmc::render
