#include "bench/experiments/output_text.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <iomanip>
#include <sstream>

namespace svmp::experiments {

std::string jsonString(const std::string& text) {
  std::string out = "\"";
  for (unsigned char c : text) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      default:
        if (c < 0x20) {
          char buffer[8];
          std::snprintf(buffer, sizeof buffer, "\\u%04x", c);
          out += buffer;
        } else {
          out += static_cast<char>(c);
        }
    }
  }
  return out + "\"";
}

std::string safeFileName(const std::string& text) {
  std::string out;
  for (char c : text) {
    const bool ok = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '.' ||
                    c == '_' || c == '-';
    out += ok ? c : '_';
  }
  const size_t first = out.find_first_not_of('.');
  out = first == std::string::npos ? "" : out.substr(first);
  // File systems take names of 255 bytes; the caller adds a suffix. A long name keeps its first 100
  // characters and a hash of the whole, so two long names still differ.
  if (out.size() > 120) {
    char hash[17];
    std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(std::hash<std::string>{}(text)));
    out = out.substr(0, 100) + "_" + hash;
  }
  return out.empty() ? "_" : out;
}

Stats statsOf(std::vector<double> v) {
  Stats s;
  s.count = static_cast<int>(v.size());
  if (v.empty()) return s;
  for (double x : v) s.mean += x;
  s.mean /= v.size();
  for (double x : v) s.std += (x - s.mean) * (x - s.mean);
  s.std = v.size() > 1 ? std::sqrt(s.std / (v.size() - 1)) : 0;
  std::sort(v.begin(), v.end());
  s.median = v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
  return s;
}

std::string jsonStats(const Stats& s) {
  // JSON has no inf or nan (a clearance with no obstacle at all is infinite): null.
  auto number = [](double v) {
    std::ostringstream o;
    o << std::setprecision(10) << v;
    return std::isfinite(v) ? o.str() : "null";
  };
  return "{\"mean\": " + number(s.mean) + ", \"std\": " + number(s.std) + ", \"median\": " + number(s.median) +
         ", \"n\": " + std::to_string(s.count) + "}";
}

// std::setw counts bytes; "±" is two, so pad by code points instead.
std::string pad(const std::string& text, size_t width) {
  size_t points = 0;
  for (unsigned char c : text) points += (c & 0xC0) != 0x80;
  return text + std::string(points < width ? width - points : 1, ' ');
}

std::string meanStd(const Stats& s, int precision) {
  if (s.count == 0) return "-";
  std::ostringstream o;
  if (std::isfinite(s.mean))
    o << std::fixed << std::setprecision(precision) << s.mean << " ± " << s.std;
  else
    o << s.mean;  // inf: no obstacle to be near
  return o.str();
}

std::string svgNumber(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.2f", v);
  return buffer;
}

std::string escapeXml(const std::string& text) {
  std::string out;
  for (size_t i = 0; i < text.size(); ++i) {
    const char ch = text[i];
    const bool control = static_cast<unsigned char>(ch) < 0x20 && ch != '\t' && ch != '\n' && ch != '\r';
    // U+FFFE and U+FFFF (EF BF BE / BF): like the control characters, not characters of XML 1.0.
    const bool nonchar = text.compare(i, 2, "\xEF\xBF") == 0 && i + 2 < text.size() &&
                         (text[i + 2] == '\xBE' || text[i + 2] == '\xBF');
    if (nonchar) {
      out += '?';
      i += 2;
      continue;
    }
    // XML 1.0 has no way to write the other control characters, not even as references.
    out += ch == '&' ? "&amp;" : ch == '<' ? "&lt;" : ch == '>' ? "&gt;" : control ? "?" : std::string(1, ch);
  }
  return out;
}

}  // namespace svmp::experiments
