#include "cspace/scenario/parameters.hpp"

#include <charconv>
#include <cmath>
#include <sstream>

#include "cspace/scenario/yaml_reader.hpp"

namespace svmp::cspace {

std::string parameterText(double v) {
  char buf[64];
  return std::string(buf, std::to_chars(buf, buf + sizeof(buf), v).ptr);
}

std::string ParameterSet::field(const std::string& key) const {
  const auto it = sources_.find(key);
  return (it != sources_.end() ? it->second : source_) + ": field '" + prefix_ + key + "'";
}

double ParameterSet::getDouble(const std::string& key, double fallback, double min, double max) const {
  used_.insert(key);
  declared_[key] = {ParameterDeclaration::Kind::kDouble, parameterText(fallback), parameterText(min) + ":" + parameterText(max)};
  auto it = values_.find(key);
  if (it == values_.end()) return fallback;
  double v = 0;  // the scenario's own number syntax (pi/2 included; no hexadecimal, no blanks)
  if (!scenario_yaml::parseNumber(it->second, v) || !std::isfinite(v))
    throw ScenarioError(field(key) + ": expected a finite number, got '" + it->second + "'");
  if (v < min || v > max) {
    std::ostringstream err;
    err << field(key) << ": must lie in [" << min << ", " << max << "], got " << it->second;
    throw ScenarioError(err.str());
  }
  return v;
}

long ParameterSet::getInt(const std::string& key, long fallback, long min, long max) const {
  used_.insert(key);
  declared_[key] = {ParameterDeclaration::Kind::kInt, std::to_string(fallback),
                    std::to_string(min) + ":" + std::to_string(max)};
  auto it = values_.find(key);
  if (it == values_.end()) return fallback;
  const std::string& s = it->second;
  const char* begin = s.data() + (s.size() > 1 && s[0] == '+' && s[1] != '-' ? 1 : 0);
  long v = 0;
  const auto [ptr, ec] = std::from_chars(begin, s.data() + s.size(), v);
  if (s.empty() || ptr != s.data() + s.size() || ec != std::errc())
    throw ScenarioError(field(key) + ": expected an integer, got '" + it->second + "'");
  if (v < min || v > max)
    throw ScenarioError(field(key) + ": must lie in [" + std::to_string(min) + ", " +
                        std::to_string(max) + "], got " + it->second);
  return v;
}

bool ParameterSet::getBool(const std::string& key, bool fallback) const {
  used_.insert(key);
  declared_[key] = {ParameterDeclaration::Kind::kBool, fallback ? "1" : "0", "0,1"};
  auto it = values_.find(key);
  if (it == values_.end()) return fallback;
  if (it->second == "true" || it->second == "1") return true;
  if (it->second == "false" || it->second == "0") return false;
  throw ScenarioError(field(key) + ": expected true or false, got '" + it->second + "'");
}

std::string ParameterSet::getString(const std::string& key, const std::string& fallback,
                                    const std::set<std::string>& allowed) const {
  used_.insert(key);
  std::string range;
  for (const auto& a : allowed) range += (range.empty() ? "" : ",") + a;
  declared_[key] = {ParameterDeclaration::Kind::kString, fallback, range};
  auto it = values_.find(key);
  if (it == values_.end()) return fallback;
  if (!allowed.empty() && !allowed.count(it->second)) {
    std::string options;
    for (const auto& a : allowed) options += (options.empty() ? "" : ", ") + a;
    throw ScenarioError(field(key) + ": expected one of " + options + ", got '" + it->second + "'");
  }
  return it->second;
}

void ParameterSet::requireAllUsed() const {
  for (const auto& [key, value] : values_)
    if (!used_.count(key))
      throw ScenarioError(field(key) + ": unknown parameter (value '" + value + "')");
}

}  // namespace svmp::cspace
