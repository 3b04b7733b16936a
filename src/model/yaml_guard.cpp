#include <fmt/format.h>

#include <limits>
#include <optional>
#include <vector>

#include "model/source_text.hpp"

namespace lagrange::model {

namespace {

/// Length of the UTF-8 sequence starting at s[i], or 0 if it is not valid UTF-8.
size_t utf8_length(const std::string& s, size_t i) {
  auto b = static_cast<unsigned char>(s[i]);
  size_t n = b < 0x80 ? 1 : (b >> 5) == 0x6 ? 2 : (b >> 4) == 0xe ? 3 : (b >> 3) == 0x1e ? 4 : 0;
  if (n == 0 || i + n > s.size()) return 0;
  for (size_t k = 1; k < n; ++k)
    if ((static_cast<unsigned char>(s[i + k]) >> 6) != 0x2) return 0;
  return n;
}

/// Bytes that are neither printable text nor tab / newline / carriage return, and invalid UTF-8.
void check_bytes(const SourceText& src) {
  const std::string& s = src.text();
  int line = 1, column = 1;
  for (size_t i = 0; i < s.size();) {
    auto b = static_cast<unsigned char>(s[i]);
    size_t n = utf8_length(s, i);
    bool control = (b < 0x20 && b != '\t' && b != '\n' && b != '\r') || b == 0x7f;
    if (control || n == 0)
      throw ModelError(SourceLoc{src.file(), line, column},
                       fmt::format("expected UTF-8 text, got byte 0x{:02x} (binary data?)", b));
    if (b == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
    i += n;
  }
}

/// Line scanner that tracks block indentation levels, flow brackets, quotes and block scalars.
class NestingScanner {
 public:
  NestingScanner(const SourceText& src, int max_depth) : src_(src), max_(max_depth) {}

  void run() {
    const std::string& s = src_.text();
    size_t start = 0;
    for (int line = 1; start <= s.size(); ++line) {
      size_t end = s.find('\n', start);
      if (end == std::string::npos) end = s.size();
      std::string text = s.substr(start, end - start);
      if (!text.empty() && text.back() == '\r') text.pop_back();
      scan_line(text, line);
      start = end + 1;
    }
    if (quote_ != 0)
      throw ModelError(
          SourceLoc{src_.file(), quote_line_, quote_column_},
          fmt::format("expected a closing {} for the quoted text starting here, got the end of "
                      "the file",
                      quote_));
  }

  /// The first tab in the leading whitespace of a block-context line, if any.
  const std::optional<SourceLoc>& indentation_tab() const { return tab_; }

 private:
  void fail(int line, size_t col) const {
    throw ModelError(SourceLoc{src_.file(), line, static_cast<int>(col) + 1},
                     fmt::format("expected at most {} levels of YAML nesting, got more", max_));
  }

  void scan_line(const std::string& t, int line) {
    if (quote_ == 0 && flow_ == 0 && block_indent_ < 0 && !tab_) note_tab(t, line);
    size_t indent = t.find_first_not_of(' ');
    bool blank = indent == std::string::npos || t[indent] == '#';
    if (block_indent_ >= 0) {
      if (blank || static_cast<int>(indent) > block_indent_) return;
      block_indent_ = -1;
    }
    size_t pos = 0;
    if (quote_ == 0 && flow_ == 0) {
      if (blank) return;
      while (!levels_.empty() && levels_.back() > indent) levels_.pop_back();
      if (levels_.empty() || levels_.back() < indent) levels_.push_back(indent);
      pos = indent;
      while (pos < t.size() && t[pos] == '-' && (pos + 1 == t.size() || t[pos + 1] == ' ')) {
        pos = t.find_first_not_of(' ', pos + 1);
        if (pos == std::string::npos) pos = t.size();
        if (levels_.back() < pos) levels_.push_back(pos);
      }
      if (static_cast<int>(levels_.size()) > max_) fail(line, pos);
      line_indent_ = static_cast<int>(indent);
    }
    bool value_start = quote_ == 0;
    for (size_t i = pos; i < t.size(); ++i) {
      char c = t[i];
      if (quote_ != 0) {
        if (quote_ == '"' && c == '\\') {
          ++i;
        } else if (c == quote_) {
          if (quote_ == '\'' && i + 1 < t.size() && t[i + 1] == '\'') {
            ++i;
          } else {
            quote_ = 0;
          }
        }
        continue;
      }
      bool after_space = i == 0 || t[i - 1] == ' ' || t[i - 1] == '\t';
      if (c == ' ' || c == '\t') continue;
      if (c == '#' && after_space) return;
      if ((c == '"' || c == '\'') && value_start) {
        quote_ = c;
        quote_line_ = line;
        quote_column_ = static_cast<int>(i) + 1;
      } else if ((c == '[' || c == '{') && (flow_ > 0 || value_start)) {
        ++flow_;
        if (static_cast<int>(levels_.size()) + flow_ > max_) fail(line, i);
      } else if ((c == ']' || c == '}') && flow_ > 0) {
        --flow_;
      } else if ((c == '|' || c == '>') && value_start && flow_ == 0) {
        block_indent_ = line_indent_;
        return;
      }
      value_start = (c == ':' || c == '-' || c == '?') && (i + 1 == t.size() || t[i + 1] == ' ');
      if (flow_ > 0 && (c == '[' || c == '{' || c == ',')) value_start = true;
    }
  }

  // YAML forbids tabs in indentation (yaml-cpp also before a comment); a blank line may hold tabs.
  void note_tab(const std::string& t, int line) {
    const size_t content = t.find_first_not_of(" \t\r");
    if (content == std::string::npos) return;
    const size_t tab = t.find('\t');
    if (tab < content) tab_ = SourceLoc{src_.file(), line, static_cast<int>(tab) + 1};
  }

  const SourceText& src_;
  std::optional<SourceLoc> tab_;
  int max_;
  std::vector<size_t> levels_;
  int flow_ = 0;
  char quote_ = 0;
  int quote_line_ = 0, quote_column_ = 0;
  int block_indent_ = -1;
  int line_indent_ = 0;
};

}  // namespace

void check_yaml_text(const SourceText& src, int max_depth) {
  check_bytes(src);
  NestingScanner(src, max_depth).run();
}

std::optional<SourceLoc> indentation_tab(const SourceText& src) {
  NestingScanner scanner(src, std::numeric_limits<int>::max());
  scanner.run();  // check_yaml_text has passed: no unclosed quote, no excessive nesting
  return scanner.indentation_tab();
}

}  // namespace lagrange::model
