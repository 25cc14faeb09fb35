#include "statmc/render/tokenizer.h"

#include <cctype>
#include <cmath>
#include <cstdlib>

namespace statmc::render {

std::vector<Token> tokenize(const std::string& text, const std::string& file)
{
    std::vector<Token> tokens;
    int line = 1;
    std::size_t i = 0;
    const std::size_t n = text.size();
    auto fail = [&](const std::string& what) {
        throw SceneError(file + ":" + std::to_string(line) + ": " + what);
    };
    while (i < n) {
        const char c = text[i];
        if (c == '\n') {
            ++line;
            ++i;
        } else if (std::isspace(static_cast<unsigned char>(c))) {
            ++i;
        } else if (c == '#') {
            while (i < n && text[i] != '\n')
                ++i;
        } else if (c == '[' || c == ']') {
            tokens.push_back({c == '[' ? Token::Kind::OpenBracket : Token::Kind::CloseBracket,
                              std::string(1, c), 0, line});
            ++i;
        } else if (c == '"') {
            const int start_line = line;
            std::string s;
            ++i;
            while (i < n && text[i] != '"') {
                if (text[i] == '\n')
                    fail("unterminated string");
                if (text[i] == '\\' && i + 1 < n) {
                    ++i;
                    s += text[i] == 'n' ? '\n' : text[i];
                } else {
                    s += text[i];
                }
                ++i;
            }
            if (i >= n)
                fail("unterminated string");
            ++i;
            tokens.push_back({Token::Kind::String, s, 0, start_line});
        } else if (std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '+' ||
                   c == '.') {
            const std::size_t start = i;
            while (i < n && (std::isalnum(static_cast<unsigned char>(text[i])) || text[i] == '-' ||
                             text[i] == '+' || text[i] == '.'))
                ++i;
            const std::string s = text.substr(start, i - start);
            char* end = nullptr;
            const double v = std::strtod(s.c_str(), &end);
            if (end != s.c_str() + s.size())
                fail("malformed number '" + s + "'");
            if (!std::isfinite(v))
                fail("number '" + s + "' is not finite");
            tokens.push_back({Token::Kind::Number, s, v, line});
        } else if (std::isalpha(static_cast<unsigned char>(c))) {
            const std::size_t start = i;
            while (i < n && (std::isalnum(static_cast<unsigned char>(text[i])) || text[i] == '_'))
                ++i;
            std::string word = text.substr(start, i - start);
            // No pbrt directive is spelt so; strtod would read them as numbers.
            std::string lower;
            for (char ch : word)
                lower += char(std::tolower(static_cast<unsigned char>(ch)));
            if (lower == "nan" || lower == "inf" || lower == "infinity")
                fail("'" + word + "' is not a finite number");
            tokens.push_back({Token::Kind::Identifier, std::move(word), 0, line});
        } else {
            fail(std::string("unexpected character '") + c + "'");
        }
    }
    return tokens;
}

}  // namespace statmc::render
