#pragma once
// Internal to the scenario loader (cspace/scenario/scenario.cpp): bounded reading of YAML text and typed,
// range-checked access to its nodes. Every failure throws ScenarioError "SOURCE: field 'PATH': what",
// naming the offending value. Not part of the public API (it exposes yaml-cpp).
#include <yaml-cpp/yaml.h>

#include <Eigen/Core>
#include <string>
#include <vector>

#include "cspace/scenario/parameters.hpp"

namespace svmp::cspace::scenario_yaml {

// A plain number, or a multiple of pi for angles: "pi", "-pi/2", "0.5pi", "2pi/3". False when the text
// is anything else (trailing characters, leading blanks, hexadecimal included). Locale independent.
bool parseNumber(const std::string& s, double& v);

// The whole file, refusing directories, unreadable paths (the OS reason) and files larger than
// ScenarioLimits::kMaxFileBytes (checked before reading, and again while reading).
std::string readScenarioFile(const std::string& path);

// The single YAML document of `text`. Refuses text larger than kMaxFileBytes, NUL bytes, more than
// kMaxYamlNodes nodes (counted by a streaming pass before any tree is built), several documents,
// quoted strings left open at the end of the text (yaml-cpp silently takes the rest of the file into
// them) and syntax errors, the latter with line and column. An empty document is a Null node.
YAML::Node loadSingleDocument(const std::string& text, const std::string& source);

using KeyList = std::vector<std::string>;

class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}
  const std::string& source() const { return source_; }

  [[noreturn]] void fail(const std::string& field, const std::string& what) const;
  // A node as it appears in an error message: 'scalar', null, (missing) or flow YAML, shortened.
  static std::string text(const YAML::Node& n);
  static std::string join(const KeyList& keys);

  // `field` is the child's ("robot.type"); a parent that is not a mapping is reported under its own name.
  YAML::Node require(const YAML::Node& parent, const std::string& key, const std::string& field) const;
  void requireMap(const YAML::Node& n, const std::string& field) const;
  // A mapping whose keys are all scalars, each given once and each in `known` (an empty list accepts
  // any key). A key in `elsewhere` but not in `known` is valid for another kind of object: the error
  // then says that `what` does not take it, instead of calling it unknown.
  void checkKeys(const YAML::Node& n, const std::string& field, const KeyList& known,
                 const std::string& what = "", const KeyList& elsewhere = {}) const;
  // A sequence of at most max_size entries.
  void requireList(const YAML::Node& n, const std::string& field, size_t max_size, const std::string& what) const;

  double number(const YAML::Node& n, const std::string& field) const;
  // A number in [lo, hi]; `unit` (may be empty) is named in the error.
  double inRange(const YAML::Node& n, const std::string& field, double lo, double hi,
                 const std::string& unit = "") const;
  // A number in (0, hi].
  double positiveAtMost(const YAML::Node& n, const std::string& field, double hi) const;
  // An integer literal ([+-]digits) in [lo, hi].
  long integer(const YAML::Node& n, const std::string& field, long lo, long hi) const;
  // A list of numbers, each in [lo, hi]; size -1: any size from 1 to max_size.
  Eigen::VectorXd vector(const YAML::Node& n, const std::string& field, int size, double lo, double hi,
                         const std::string& unit = "", size_t max_size = 1000) const;
  bool boolean(const YAML::Node& n, const std::string& field) const;
  std::string string(const YAML::Node& n, const std::string& field) const;

 private:
  std::string source_;
};

// "%g" of a double, for messages.
std::string num(double v);

}  // namespace svmp::cspace::scenario_yaml
