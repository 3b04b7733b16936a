#include "model/source_text.hpp"

namespace lagrange::model {

namespace {

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r';
}

/// The first position ≥ p in `text` holding value character `c`, skipping only what YAML folding
/// and quoting insert (whitespace, quotes, backslashes); npos when the alignment is lost.
size_t align(const std::string& text, size_t p, char c) {
  while (p < text.size()) {
    char s = text[p];
    if (s == c || (is_space(c) && is_space(s))) return p;
    if (!is_space(s) && s != '\'' && s != '"' && s != '\\') return std::string::npos;
    ++p;
  }
  return std::string::npos;
}

}  // namespace

SourceLoc SourceText::at(const YAML::Mark& mark) const {
  if (mark.is_null() || mark.line < 0) return SourceLoc{file_, 0, 0};
  return SourceLoc{file_, mark.line + 1, mark.column + 1};
}

SourceLoc SourceText::at(const YAML::Node& node, size_t offset) const {
  YAML::Mark mark = node.Mark();
  if (mark.is_null() || mark.pos < 0 || static_cast<size_t>(mark.pos) > text_.size() ||
      !node.IsScalar())
    return at(mark);
  const std::string& value = node.Scalar();
  size_t p = static_cast<size_t>(mark.pos);
  if (p < text_.size() && (text_[p] == '|' || text_[p] == '>')) {
    while (p < text_.size() && text_[p] != '\n') ++p;
  } else if (p < text_.size() && (text_[p] == '"' || text_[p] == '\'')) {
    ++p;
  }
  size_t target = p;
  for (size_t i = 0; i <= offset && i < value.size(); ++i) {
    size_t q = align(text_, p, value[i]);
    if (q == std::string::npos) break;
    target = q;
    p = q + 1;
  }
  if (offset >= value.size() && !value.empty() && target < text_.size())
    ++target;  // just past the end
  int line = mark.line, column = mark.column;
  for (size_t i = static_cast<size_t>(mark.pos); i < target && i < text_.size(); ++i) {
    if (text_[i] == '\n') {
      ++line;
      column = 0;
    } else {
      ++column;
    }
  }
  return SourceLoc{file_, line + 1, column + 1};
}

}  // namespace lagrange::model
