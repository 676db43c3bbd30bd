#include "bench/experiments/svpp_svg.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "bench/experiments/atomic_file.hpp"
#include "bench/experiments/output_text.hpp"
#include "planners/geometry.hpp"

namespace svmp::experiments {
namespace {

using planners::Point2;
using planners::SampleKind;

constexpr const char *kPositive = "#1f77b4", *kNegative = "#d62728", *kPath = "#e6ab02";
constexpr double kPanel = 300, kGap = 26, kMargin = 10, kHeader = 44;
constexpr int kShadeGrid = 90;  // cells per side of the V shading

// One square plot of the data rectangle [lo, hi] (y up) at page offset (x0, y0).
struct Panel {
  Point2 lo, hi;
  double x0, y0;
  double scale() const { return kPanel / std::max(hi.x() - lo.x(), hi.y() - lo.y()); }
  double px(double x) const { return x0 + (x - lo.x()) * scale(); }
  double py(double y) const { return y0 + kPanel - (y - lo.y()) * scale(); }
  std::string xy(const Point2& p) const { return svgNumber(px(p.x())) + "," + svgNumber(py(p.y())); }
};

void polyline(std::ostringstream& s, const Panel& panel, const std::vector<Point2>& points,
              const std::string& style, bool closed) {
  s << (closed ? "<polygon" : "<polyline") << " points=\"";
  for (const Point2& p : points) s << panel.xy(p) << ' ';
  s << "\" " << style << "/>\n";
}

// Outline of a part projected on the coordinates (a, b).
std::vector<Point2> outline(const planners::ConvexPart& part, int a, int b) {
  planners::Polygon points;
  for (Eigen::Index v = 0; v < part.vertices.cols(); ++v)
    points.emplace_back(part.vertices(a, v), part.vertices(b, v));
  return planners::convexHull(points);
}

void obstacles(std::ostringstream& s, const Panel& panel, const planners::SvppTrace& trace,
               const planners::Pattern& pattern, int a, int b) {
  for (size_t k = 0; k < trace.obstacles.size(); ++k)
    for (const auto& part : trace.obstacles[k].parts) {
      const char* colour = pattern[k] ? kPositive : kNegative;
      polyline(
          s, panel, outline(part, a, b),
          std::string("fill=\"") + colour + "\" fill-opacity=\"0.35\" stroke=\"" + colour + "\"",
          true);
    }
}

void path(std::ostringstream& s, const Panel& panel, const std::vector<Eigen::VectorXd>& points,
          bool reached, int a, int b) {
  std::vector<Point2> projected;
  for (const auto& p : points) projected.emplace_back(p[a], p[b]);
  polyline(s, panel, projected,
           std::string("fill=\"none\" stroke=\"") + kPath + "\" stroke-width=\"2.5\"" +
               (reached ? "" : " stroke-dasharray=\"5,3\""),
           false);
}

// Drawing clipped to the panel: a nested <svg> whose viewBox is the panel's page rectangle.
void openClip(std::ostringstream& s, const Panel& panel) {
  s << "<svg x=\"" << svgNumber(panel.x0) << "\" y=\"" << svgNumber(panel.y0) << "\" width=\"" << kPanel
    << "\" height=\"" << kPanel << "\" viewBox=\"" << svgNumber(panel.x0) << " " << svgNumber(panel.y0) << " "
    << kPanel << " " << kPanel << "\">\n";
}

void frame(std::ostringstream& s, const Panel& panel, const std::string& caption, bool chosen) {
  s << "<rect x=\"" << svgNumber(panel.x0) << "\" y=\"" << svgNumber(panel.y0) << "\" width=\"" << kPanel
    << "\" height=\"" << kPanel << "\" fill=\"none\" stroke=\"" << (chosen ? "red" : "black")
    << "\" stroke-width=\"" << (chosen ? 3 : 1) << "\"/>\n"
    << "<text x=\"" << svgNumber(panel.x0) << "\" y=\"" << svgNumber(panel.y0 - 5) << "\" font-size=\"11\">"
    << escapeXml(caption) << "</text>\n";
}

// Positive, intermediate and negative regions of V, runs of equal cells merged per row.
void shading(std::ostringstream& s, const Panel& panel, const svm::BinaryModel& model) {
  const Point2 cell = (panel.hi - panel.lo) / kShadeGrid;
  const char* shades[] = {"#555555", "#aaaaaa", "#eeeeee"};  // negative, intermediate, positive
  s << "<g shape-rendering=\"crispEdges\">\n";
  Eigen::Vector2d q;
  for (int j = 0; j < kShadeGrid; ++j) {
    q.y() = panel.lo.y() + (j + 0.5) * cell.y();
    int run_start = 0, run_region = -1;
    for (int i = 0; i <= kShadeGrid; ++i) {
      int region = -1;
      if (i < kShadeGrid) {
        q.x() = panel.lo.x() + (i + 0.5) * cell.x();
        const double v = model.decision(q.data());
        region = v <= -1 ? 0 : v < 1 ? 1 : 2;
      }
      if (i < kShadeGrid && region == run_region) continue;
      if (run_region >= 0)
        s << "<rect x=\"" << svgNumber(panel.px(panel.lo.x() + run_start * cell.x())) << "\" y=\""
          << svgNumber(panel.py(panel.lo.y() + (j + 1) * cell.y())) << "\" width=\""
          << svgNumber((i - run_start) * cell.x() * panel.scale()) << "\" height=\""
          << svgNumber(cell.y() * panel.scale() + 0.5) << "\" fill=\"" << shades[run_region] << "\"/>\n";
      run_start = i, run_region = region;
    }
  }
  s << "</g>\n";
}

void samples(std::ostringstream& s, const Panel& panel, const planners::SvppTrial& trial) {
  const planners::TrainingSet& set = trial.samples;
  for (double label : {1.0, -1.0}) {  // guide rows joined, as the paper's Fig. 2(d)
    std::vector<Point2> row;
    for (int i = 0; i < set.size(); ++i)
      if (set.kind[i] == SampleKind::kGuide && set.y[i] == label)
        row.emplace_back(set.X(0, i), set.X(1, i));
    polyline(s, panel, row,
             std::string("fill=\"none\" stroke=\"") + (label > 0 ? kPositive : kNegative) +
                 "\" stroke-width=\"0.6\"",
             false);
  }
  for (int i = 0; i < set.size(); ++i) {
    const Point2 p(set.X(0, i), set.X(1, i));
    const std::string colour = set.y[i] > 0 ? kPositive : kNegative;
    const double x = panel.px(p.x()), y = panel.py(p.y());
    if (set.kind[i] == SampleKind::kVirtual)
      s << "<circle cx=\"" << svgNumber(x) << "\" cy=\"" << svgNumber(y)
        << "\" r=\"2.2\" fill=\"none\" stroke=\"" << colour << "\"/>\n";
    else if (set.y[i] > 0)
      s << "<rect x=\"" << svgNumber(x - 1.6) << "\" y=\"" << svgNumber(y - 1.6)
        << "\" width=\"3.2\" height=\"3.2\" fill=\"" << colour << "\"/>\n";
    else
      s << "<path d=\"M" << svgNumber(x - 1.8) << "," << svgNumber(y - 1.8)
        << "l3.6,3.6m0,-3.6l-3.6,3.6\" stroke=\"" << colour << "\" stroke-width=\"1\"/>\n";
  }
  const Eigen::MatrixXd& sv = trial.model.supportVectors();
  for (Eigen::Index i = 0; i < sv.cols(); ++i)
    s << "<rect x=\"" << svgNumber(panel.px(sv(0, i)) - 3.5) << "\" y=\"" << svgNumber(panel.py(sv(1, i)) - 3.5)
      << "\" width=\"7\" height=\"7\" fill=\"none\" stroke=\"black\" stroke-width=\"0.7\"/>\n";
}

std::string caption(int index, const planners::SvppTrial& trial) {
  std::ostringstream c;
  c << "pattern " << index + 1 << ": " << planners::followStatusName(trial.follow.status);
  if (trial.follow.reached())
    c << ", length " << svgNumber(trial.follow.length) << (trial.valid ? "" : ", collides");
  return c.str();
}

std::string document(double width, double height, const std::string& title,
                     const std::string& subtitle, const std::string& body) {
  std::ostringstream s;
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << svgNumber(width) << "\" height=\""
    << svgNumber(height)
    << "\" font-family=\"sans-serif\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    << "<text x=\"" << kMargin << "\" y=\"18\" font-size=\"15\">" << escapeXml(title) << "</text>\n"
    << "<text x=\"" << kMargin << "\" y=\"33\" font-size=\"10\">" << escapeXml(subtitle)
    << "</text>\n"
    << body << "</svg>\n";
  return s.str();
}

}  // namespace

bool writeSvppSvg(const std::string& file, const std::string& title,
                  const planners::SvppTrace& trace, const Eigen::VectorXd& lower,
                  const Eigen::VectorXd& upper) {
  if (trace.trials.empty()) return false;
  std::ostringstream body;
  const int dim = static_cast<int>(lower.size());
  if (dim == 2) {
    const int n = static_cast<int>(trace.trials.size()), columns = std::min(n, 5),
              rows = (n + columns - 1) / columns;
    for (int t = 0; t < n; ++t) {
      const planners::SvppTrial& trial = trace.trials[t];
      const Panel panel{lower, upper, kMargin + (t % columns) * (kPanel + kGap),
                        kHeader + 14 + (t / columns) * (kPanel + kGap)};
      openClip(body, panel);
      shading(body, panel, trial.model);
      obstacles(body, panel, trace, trial.pattern, 0, 1);
      samples(body, panel, trial);
      path(body, panel, trial.follow.path, trial.valid, 0, 1);
      body << "</svg>\n";
      frame(body, panel, caption(t, trial), t == trace.chosen);
    }
    const double width = 2 * kMargin + columns * kPanel + (columns - 1) * kGap;
    const double height = kHeader + 14 + rows * (kPanel + kGap);
    writeFileAtomically(
        file,
        document(
            width, height, title,
            "one panel per pattern tried; shading: V >= 1 light, |V| < 1 medium, V <= -1 dark; "
            "squares/crosses: positive/negative samples, circles: virtual, lines: guides, "
            "ringed: support vectors; red frame: returned path",
            body.str()));
    return true;
  }
  const int shown = trace.chosen >= 0 ? trace.chosen : 0;
  const planners::SvppTrial& trial = trace.trials[shown];
  const int axes[3][2] = {{0, 1}, {0, 2}, {1, 2}};
  const char* names[3] = {"x-y", "x-z", "y-z"};
  for (int v = 0; v < 3; ++v) {
    const int a = axes[v][0], b = axes[v][1];
    const Panel panel{Point2(lower[a], lower[b]), Point2(upper[a], upper[b]),
                      kMargin + v * (kPanel + kGap), kHeader + 14};
    openClip(body, panel);
    obstacles(body, panel, trace, trial.pattern, a, b);
    const Eigen::MatrixXd& sv = trial.model.supportVectors();
    for (Eigen::Index i = 0; i < sv.cols(); ++i)
      body << "<circle cx=\"" << svgNumber(panel.px(sv(a, i))) << "\" cy=\"" << svgNumber(panel.py(sv(b, i)))
           << "\" r=\"1.8\" fill=\"" << (trial.model.coefficients()[i] > 0 ? kPositive : kNegative)
           << "\"/>\n";
    path(body, panel, trial.follow.path, trial.valid, a, b);
    body << "</svg>\n";
    frame(body, panel, std::string(names[v]) + " projection", false);
  }
  writeFileAtomically(
      file, document(2 * kMargin + 3 * kPanel + 2 * kGap, kHeader + 14 + kPanel + kGap, title,
                     caption(shown, trial) + " (" + std::to_string(trace.trials.size()) +
                         " patterns tried); obstacles blue positive / red negative, dots: support "
                         "vectors by label, yellow: path",
                     body.str()));
  return true;
}

}  // namespace svmp::experiments
