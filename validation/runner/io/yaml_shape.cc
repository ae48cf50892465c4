#include "validation/runner/io/yaml_shape.h"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/exceptions.h>
#include <yaml-cpp/parser.h>

#include <map>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace phdslam::validation {
namespace {

// Walks the parser's events; throws on the first violation.
class ShapeChecker : public YAML::EventHandler {
 public:
  explicit ShapeChecker(const std::string& source) : source_(source) {}

  void OnDocumentStart(const YAML::Mark& mark) override {
    if (++documents_ > 1) {
      Fail(mark, "a second YAML document ('---'): an experiment file holds exactly one");
    }
  }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& mark, YAML::anchor_t) override { Node(mark, "~"); }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t) override {
    Fail(mark, "YAML aliases (*name) are not accepted in experiment files; write the value out");
  }
  void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                const std::string& value) override {
    Node(mark, value);
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {
    Open(mark, false);
  }
  void OnSequenceEnd() override { frames_.pop_back(); }
  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {
    Open(mark, true);
  }
  void OnMapEnd() override { frames_.pop_back(); }

 private:
  struct Frame {
    bool map = false;
    bool key_next = true;
    std::map<std::string, int> key_lines;
  };

  [[noreturn]] void Fail(const YAML::Mark& mark, const std::string& message) const {
    throw std::invalid_argument(source_ + ":" + std::to_string(mark.line + 1) + ": " + message);
  }

  // Counts a node and, in a mapping, alternates between keys and values; `key` is the node's
  // text when it is a scalar that may serve as a key.
  void Node(const YAML::Mark& mark, const std::string& key) {
    if (++nodes_ > kMaxYamlNodes) {
      Fail(mark, "more than " + std::to_string(kMaxYamlNodes) + " values in one file");
    }
    if (frames_.empty() || !frames_.back().map) return;
    Frame& frame = frames_.back();
    if (frame.key_next && !key.empty()) {
      const auto [it, added] = frame.key_lines.emplace(key, mark.line + 1);
      if (!added) {
        Fail(mark, "the key '" + key + "' appears twice in one mapping (first on line " +
                       std::to_string(it->second) + ")");
      }
    }
    frame.key_next = !frame.key_next;
  }

  void Open(const YAML::Mark& mark, bool map) {
    Node(mark, "");
    if (frames_.size() >= kMaxYamlDepth) {
      Fail(mark, "nested deeper than " + std::to_string(kMaxYamlDepth) + " levels");
    }
    frames_.push_back({map, true, {}});
  }

  const std::string& source_;
  std::vector<Frame> frames_;
  std::size_t nodes_ = 0;
  std::size_t documents_ = 0;
};

}  // namespace

void CheckYamlShape(std::string_view text, const std::string& source) {
  std::istringstream in{std::string(text)};
  ShapeChecker checker(source);
  try {
    YAML::Parser parser(in);
    while (parser.HandleNextDocument(checker)) {
    }
  } catch (const YAML::ParserException& e) {
    throw std::invalid_argument(source + ": line " + std::to_string(e.mark.line + 1) + ", column " +
                                std::to_string(e.mark.column + 1) +
                                ": YAML syntax error: " + e.msg);
  }
}

}  // namespace phdslam::validation
