#pragma once
// The model file's text, used to turn yaml-cpp marks and offsets inside scalars into
// file:line:column.

#include <yaml-cpp/yaml.h>

#include <optional>
#include <string>

#include "lagrange/error.hpp"

namespace lagrange::model {

/// Raw text of a model file plus its label; maps YAML positions to 1-based SourceLoc.
class SourceText {
 public:
  SourceText(std::string text, std::string file) : text_(std::move(text)), file_(std::move(file)) {}

  const std::string& text() const { return text_; }
  const std::string& file() const { return file_; }

  /// Location of a 0-based yaml-cpp mark (a null mark gives the file alone).
  SourceLoc at(const YAML::Mark& mark) const;
  /// Location of a node's start.
  SourceLoc at(const YAML::Node& node) const { return at(node.Mark()); }
  /// Location of byte `offset` of a scalar node's value: exact for plain and quoted one-line
  /// scalars, aligned character by character for folded, multi-line and block scalars.
  SourceLoc at(const YAML::Node& node, size_t offset) const;

 private:
  std::string text_;
  std::string file_;
};

/// Reject input yaml-cpp should not see: non-text bytes, invalid UTF-8, and nesting of flow
/// brackets plus block indentation deeper than `max_depth` (yaml-cpp recurses per level).
void check_yaml_text(const SourceText& src, int max_depth = 200);

/// The first tab in the indentation of a block-context line (YAML forbids it), if any: used to
/// explain a yaml-cpp syntax error, which does not mention the tab.
std::optional<SourceLoc> indentation_tab(const SourceText& src);

/// Reject streams with more than one document, and those where yaml-cpp 0.7 makes no progress
/// (a leading ',' sends YAML::LoadAll into an endless loop, yaml-cpp issue #1040).
void check_single_document(const SourceText& src);

}  // namespace lagrange::model
