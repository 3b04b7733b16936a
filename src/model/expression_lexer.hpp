#pragma once
// Tokens of the model expression language (docs/model-language.md, "Expressions").

#include <cstddef>
#include <string>
#include <vector>

namespace lagrange::model {

/// What a token is; operators and brackets are single characters kept in Token::text.
enum class TokenKind { Number, Name, Symbol, End };

/// One token with its byte offset inside the expression text.
struct Token {
  TokenKind kind;
  std::string text;
  size_t offset = 0;
};

/// A mistake inside an expression, located by byte offset in the expression text.
struct ExprError {
  size_t offset;
  std::string message;
};

/// `text` cut to at most `max` bytes (with "..." appended when cut), for quoting input in messages.
std::string clip(const std::string& text, size_t max = 40);

/// Split an expression into tokens (ending with an End token). Throws ExprError on a stray
/// character.
std::vector<Token> tokenize(const std::string& text);

}  // namespace lagrange::model
