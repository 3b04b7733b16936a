#include "model/expression_lexer.hpp"

#include <fmt/format.h>

#include <cctype>

namespace lagrange::model {

namespace {

bool is_name_start(char c) {
  return std::isalpha(static_cast<unsigned char>(c)) || c == '_';
}
bool is_name_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}
bool is_digit(char c) {
  return std::isdigit(static_cast<unsigned char>(c)) != 0;
}

/// Length of the number starting at `i`: digits [. digits] [e [+-] digits], or .digits.
size_t number_length(const std::string& s, size_t i) {
  size_t j = i;
  while (j < s.size() && is_digit(s[j])) ++j;
  if (j < s.size() && s[j] == '.' && (j > i || (j + 1 < s.size() && is_digit(s[j + 1])))) {
    ++j;
    while (j < s.size() && is_digit(s[j])) ++j;
  }
  if (j < s.size() && (s[j] == 'e' || s[j] == 'E')) {
    size_t k = j + 1;
    if (k < s.size() && (s[k] == '+' || s[k] == '-')) ++k;
    if (k < s.size() && is_digit(s[k])) {
      while (k < s.size() && is_digit(s[k])) ++k;
      j = k;
    }
  }
  return j - i;
}

std::string describe_char(char c) {
  auto u = static_cast<unsigned char>(c);
  if (std::isprint(u)) return fmt::format("'{}'", c);
  return fmt::format("byte 0x{:02x}", u);
}

}  // namespace

std::string clip(const std::string& text, size_t max) {
  return text.size() <= max ? text : text.substr(0, max) + "...";
}

std::vector<Token> tokenize(const std::string& text) {
  std::vector<Token> out;
  size_t i = 0;
  while (i < text.size()) {
    char c = text[i];
    if (std::isspace(static_cast<unsigned char>(c))) {
      ++i;
    } else if (is_digit(c) || (c == '.' && i + 1 < text.size() && is_digit(text[i + 1]))) {
      size_t n = number_length(text, i);
      out.push_back({TokenKind::Number, text.substr(i, n), i});
      i += n;
    } else if (is_name_start(c)) {
      size_t j = i + 1;
      while (j < text.size() && is_name_char(text[j])) ++j;
      out.push_back({TokenKind::Name, text.substr(i, j - i), i});
      i = j;
    } else if (std::string("+-*/^()[],.").find(c) != std::string::npos) {
      out.push_back({TokenKind::Symbol, std::string(1, c), i});
      ++i;
    } else {
      // x' (Newton's prime) is not a derivative here: say what is.
      throw ExprError{
          i, fmt::format("expected an operator, a name or a number, got {}{}", describe_char(c),
                         c == '\'' ? " (a time derivative is written der(x))" : "")};
    }
  }
  out.push_back({TokenKind::End, "", text.size()});
  return out;
}

}  // namespace lagrange::model
