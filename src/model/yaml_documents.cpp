#include <fmt/format.h>
#include <yaml-cpp/eventhandler.h>

#include <sstream>

#include "model/source_text.hpp"

namespace lagrange::model {

namespace {

/// Records where a document starts and ignores its content.
class DocumentStart : public YAML::EventHandler {
 public:
  YAML::Mark start = YAML::Mark::null_mark();
  void OnDocumentStart(const YAML::Mark& mark) override { start = mark; }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t,
                const std::string&) override {}
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {}
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {}
  void OnMapEnd() override {}
};

}  // namespace

void check_single_document(const SourceText& src) {
  std::istringstream in(src.text());
  YAML::Parser parser(in);
  DocumentStart first, second;
  if (!parser.HandleNextDocument(first) || !parser.HandleNextDocument(second)) return;
  if (second.start.pos == first.start.pos)
    throw ModelError(src.at(second.start),
                     fmt::format("expected valid YAML, got '{}' where no YAML token can start",
                                 src.text().substr(static_cast<size_t>(second.start.pos), 1)));
  throw ModelError(src.at(second.start), "expected one YAML document, got more");
}

}  // namespace lagrange::model
