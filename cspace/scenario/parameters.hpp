#pragma once
// Planner parameters as given in a scenario file (`planners: {svmp: {sigma: 0.3}}`) and overridden per run
// (`--set svmp.sigma=0.25`). Values stay text until a planner reads them with its own bounds, so every
// error names the source, the field and the value; keys no planner reads are reported as typos.
// Thread safety: none (getters record which keys were read); one reader at a time.
#include <map>
#include <set>
#include <stdexcept>
#include <string>

namespace svmp::cspace {

// Bad input in a scenario file or on the command line; what() names file, field and value.
class ScenarioError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// What a getter was asked for: the value's kind, the default it was given and its bounds or allowed
// values, as text. planners/ompl/ declares a planner's OMPL parameters (ompl::base::ParamSet) from these.
struct ParameterDeclaration {
  enum class Kind { kDouble, kInt, kBool, kString };
  Kind kind = Kind::kString;
  std::string fallback;
  std::string range;  // OMPL's range-suggestion convention: "min:max", "0,1" or "a,b,c"
};

// The shortest text that reads back as the same double (how declarations and OMPL's ParamSet write
// numbers).
std::string parameterText(double v);

class ParameterSet {
 public:
  ParameterSet() = default;
  ParameterSet(std::string source, std::string prefix, std::map<std::string, std::string> values)
      : source_(std::move(source)), prefix_(std::move(prefix)), values_(std::move(values)) {}

  // `source` names where the value came from when that is not the scenario file ("flag --set"), so
  // an error about it blames the right place.
  void set(const std::string& key, const std::string& value, const std::string& source = "") {
    values_[key] = value;
    if (!source.empty()) sources_[key] = source;
  }
  bool has(const std::string& key) const { return values_.count(key) > 0; }
  // Each getter returns the fallback when the key is absent and throws ScenarioError when the value
  // does not parse or lies outside [min, max].
  double getDouble(const std::string& key, double fallback, double min = -1e300, double max = 1e300) const;
  long getInt(const std::string& key, long fallback, long min = -(1L << 62), long max = 1L << 62) const;
  bool getBool(const std::string& key, bool fallback) const;
  std::string getString(const std::string& key, const std::string& fallback,
                        const std::set<std::string>& allowed = {}) const;
  // Throws ScenarioError naming keys that were set but never read.
  void requireAllUsed() const;
  // Where `key` is set, for an error about it: "FILE: field 'planners.P.KEY'", or the flag that set it.
  std::string describe(const std::string& key) const { return field(key); }
  const std::map<std::string, std::string>& values() const { return values_; }
  // Every key a getter read, with its kind, default and bounds (in the order of the keys).
  const std::map<std::string, ParameterDeclaration>& declarations() const { return declared_; }

 private:
  std::string field(const std::string& key) const;
  std::string source_, prefix_;
  std::map<std::string, std::string> values_;
  std::map<std::string, std::string> sources_;  // per key, when set from elsewhere than source_
  mutable std::set<std::string> used_;
  mutable std::map<std::string, ParameterDeclaration> declared_;
};

}  // namespace svmp::cspace
