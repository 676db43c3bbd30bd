#include "bench/experiments/svg_writer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "bench/experiments/atomic_file.hpp"
#include "bench/experiments/output_text.hpp"
#include "cspace/collision_checker.hpp"
#include "planners/geometry.hpp"
#include "robots/point_robot.hpp"

namespace svmp::experiments {
namespace {

using Point = planners::Point2;
using Polygon = planners::Polygon;

constexpr const char* kPalette[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd",
                                    "#8c564b", "#e377c2", "#bcbd22", "#17becf"};
constexpr const char* kPathColour = "#d62728";  // not in the palette
constexpr int kGrid = 150;                      // cells per side of the C-space grids
constexpr int kArcPoints = 48;                  // points per circle of a projected round shape
constexpr double kLeft = 55, kRight = 20, kTop = 58, kBottom = 42;  // margins around the plot, px

// Colour of an obstacle class; ids start at 1, ids below (joint limits, self-collision) are grey.
const char* classColour(int obstacle_id) {
  return obstacle_id < 1 ? "#7f7f7f" : kPalette[(obstacle_id - 1) % 8];
}

// A plot of the y-up data rectangle [lower, upper] on the y-down SVG page, aspect ratio kept within
// [1/3, 3] (equal scales unless that would flatten the plot).
class Canvas {
 public:
  Canvas(Point lower, Point upper, double max_side = 600) : lower_(lower), upper_(upper) {
    const Point extent = upper - lower;
    const double aspect = std::clamp(extent.y() / extent.x(), 1.0 / 3, 3.0);
    width_ = aspect <= 1 ? max_side : max_side / aspect;
    height_ = width_ * aspect;
    scale_ = Point(width_ / extent.x(), height_ / extent.y());
  }
  double px(double x) const { return kLeft + (x - lower_.x()) * scale_.x(); }
  double py(double y) const { return kTop + (upper_.y() - y) * scale_.y(); }
  std::string xy(const Point& p) const { return svgNumber(px(p.x())) + "," + svgNumber(py(p.y())); }
  std::ostringstream& out() { return body_; }

  void polyline(const Polygon& points, const std::string& style, bool closed = false) {
    body_ << (closed ? "<polygon" : "<polyline") << " points=\"";
    for (const Point& p : points) body_ << xy(p) << ' ';
    body_ << "\" " << style << "/>\n";
  }
  // r in px.
  void circle(const Point& c, double r, const std::string& style) {
    body_ << "<circle cx=\"" << svgNumber(px(c.x())) << "\" cy=\"" << svgNumber(py(c.y())) << "\" r=\""
          << svgNumber(r) << "\" " << style << "/>\n";
  }
  void rect(const Point& lo, const Point& hi, const std::string& style) {
    body_ << "<rect x=\"" << svgNumber(px(lo.x())) << "\" y=\"" << svgNumber(py(hi.y())) << "\" width=\""
          << svgNumber((hi.x() - lo.x()) * scale_.x()) << "\" height=\""
          << svgNumber((hi.y() - lo.y()) * scale_.y()) << "\" " << style << "/>\n";
  }
  // A marker of half-size h px: a square, or a diamond.
  void marker(const Point& c, double h, bool diamond, const std::string& style) {
    const double x = px(c.x()), y = py(c.y());
    const double dx[4] = {-h, h, h, -h}, dy[4] = {-h, -h, h, h};
    body_ << "<polygon points=\"";
    for (int i = 0; i < 4; ++i)
      body_ << svgNumber(x + (diamond ? (dx[i] - dy[i]) / 1.4 : dx[i])) << ','
            << svgNumber(y + (diamond ? (dx[i] + dy[i]) / 1.4 : dy[i])) << ' ';
    body_ << "\" " << style << "/>\n";
  }

  // The whole document: title, legend (colour, name), the plot clipped to its frame, axes labelled
  // with their bounds.
  std::string document(const std::string& title, const std::string& subtitle,
                       const std::vector<std::pair<std::string, std::string>>& legend,
                       const std::string& x_name, const std::string& y_name) const {
    const double w = kLeft + width_ + kRight, h = kTop + height_ + kBottom;
    const double right = kLeft + width_, bottom = kTop + height_;
    std::ostringstream s;
    const auto text = [&s](double x, double y, const char* anchor, int size, const std::string& t) {
      s << "<text x=\"" << svgNumber(x) << "\" y=\"" << svgNumber(y) << "\" text-anchor=\"" << anchor
        << "\" font-size=\"" << size << "\">" << escapeXml(t) << "</text>\n";
    };
    const std::string frame = "x=\"" + svgNumber(kLeft) + "\" y=\"" + svgNumber(kTop) + "\" width=\"" +
                              svgNumber(width_) + "\" height=\"" + svgNumber(height_) + "\"";
    s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << svgNumber(w) << "\" height=\"" << svgNumber(h)
      << "\" font-family=\"sans-serif\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      << "<clipPath id=\"plot\"><rect " << frame << "/></clipPath>\n";
    text(kLeft, 18, "start", 15, title);
    text(kLeft, 33, "start", 10, subtitle);
    double x = kLeft;
    for (const auto& [colour, name] : legend) {
      s << "<rect x=\"" << svgNumber(x) << "\" y=\"40\" width=\"10\" height=\"10\" fill=\"" << colour
        << "\"/>\n";
      text(x + 13, 49, "start", 10, name);
      x += 22 + 6.0 * name.size();
    }
    s << "<g clip-path=\"url(#plot)\">\n"
      << body_.str() << "</g>\n<rect " << frame << " fill=\"none\" stroke=\"black\"/>\n";
    text(kLeft, bottom + 15, "middle", 11, svgNumber(lower_.x()));
    text(right, bottom + 15, "middle", 11, svgNumber(upper_.x()));
    text(kLeft + width_ / 2, bottom + 32, "middle", 11, x_name);
    text(kLeft - 4, bottom, "end", 11, svgNumber(lower_.y()));
    text(kLeft - 4, kTop + 10, "end", 11, svgNumber(upper_.y()));
    text(kLeft - 8, kTop + height_ / 2, "end", 11, y_name);
    s << "</svg>\n";
    return s.str();
  }

 private:
  Point lower_, upper_, scale_;
  double width_ = 0, height_ = 0;
  std::ostringstream body_;
};

std::vector<std::pair<std::string, std::string>> obstacleLegend(const cspace::Environment& env) {
  std::vector<std::pair<std::string, std::string>> legend;
  for (const cspace::Obstacle& o : env.obstacles())
    legend.emplace_back(classColour(o.id),
                        (o.name.empty() ? "obstacle " + std::to_string(o.id) : o.name) +
                            (o.is_virtual ? " (virtual)" : ""));
  return legend;
}

// Start and goal: the path's ends, else the first query's.
bool endpoints(const SvgContent& content, Eigen::VectorXd& start, Eigen::VectorXd& goal) {
  if (content.path && !content.path->empty()) {
    start = content.path->front(), goal = content.path->back();
    return true;
  }
  if (content.scenario->queries.empty()) return false;
  start = content.scenario->queries.front().start, goal = content.scenario->queries.front().goal;
  return true;
}

// The path (thick), start (square) and goal (diamond).
void drawPathAndEnds(Canvas& canvas, const SvgContent& content) {
  if (content.path && content.path->size() > 1)
    canvas.polyline(Polygon(content.path->begin(), content.path->end()),
                    std::string("fill=\"none\" stroke=\"") + kPathColour +
                        "\" stroke-width=\"3\" stroke-linejoin=\"round\" stroke-linecap=\"round\"");
  Eigen::VectorXd start, goal;
  if (!endpoints(content, start, goal)) return;
  const std::string style = "fill=\"white\" stroke=\"black\" stroke-width=\"1.5\"";
  canvas.marker(start, 6, false, style);
  canvas.marker(goal, 6, true, style);
}

// C-obstacle regions: runs of equal grid cells along each row become one rectangle.
void drawCObstacles(Canvas& canvas, const cspace::Scenario& scenario, const Point& lo,
                    const Point& hi) {
  const cspace::CollisionChecker checker(scenario.robot, scenario.environment,
                                         scenario.self_collision);
  const Point cell = (hi - lo) / kGrid;
  Eigen::VectorXd q(2);
  canvas.out() << "<g shape-rendering=\"crispEdges\" fill-opacity=\"0.3\">\n";
  for (int j = 0; j < kGrid; ++j) {
    q[1] = lo.y() + (j + 0.5) * cell.y();
    int run_start = 0, run_id = cspace::kFree;
    for (int i = 0; i <= kGrid; ++i) {
      int id = cspace::kFree;
      if (i < kGrid) {
        q[0] = lo.x() + (i + 0.5) * cell.x();
        id = checker.check(q);
      }
      if (i < kGrid && id == run_id) continue;
      if (run_id != cspace::kFree)
        canvas.rect(lo + Point(run_start * cell.x(), j * cell.y()),
                    lo + Point(i * cell.x(), (j + 1) * cell.y()),
                    std::string("fill=\"") + classColour(run_id) + "\"");
      run_start = i, run_id = id;
    }
  }
  canvas.out() << "</g>\n";
}

// F_k = 0 (planners/geometry.hpp) as the "d" of one SVG path.
std::string zeroLevelSetPath(const Canvas& canvas, const planners::RiskFunction& risk, int k, const Point& lo,
                             const Point& hi) {
  Eigen::VectorXd q(2);
  const auto segments = planners::zeroLevelSet(
      [&](const Point& p) {
        q = p;
        return risk.decision(k, q);
      },
      lo, hi, kGrid);
  std::string d;
  for (const auto& [a, b] : segments) d.append("M").append(canvas.xy(a)).append("L").append(canvas.xy(b));
  return d;
}

// The configuration at arc length s (weighted metric) along the path; cumulative[i] = length to
// path[i].
Eigen::VectorXd pointAlong(const std::vector<Eigen::VectorXd>& path,
                           const std::vector<double>& cumulative, double s) {
  const size_t i = std::upper_bound(cumulative.begin(), cumulative.end(), s) - cumulative.begin();
  if (i == 0) return path.front();
  if (i >= path.size()) return path.back();
  const double span = cumulative[i] - cumulative[i - 1];
  const double t = span > 0 ? (s - cumulative[i - 1]) / span : 0;
  return path[i - 1] + t * (path[i] - path[i - 1]);
}

void extend(Point& lo, Point& hi, const Polygon& points) {
  for (const Point& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
}

}  // namespace

bool writeConfigurationSpaceSvg(const std::string& file, const SvgContent& content) {
  if (!content.scenario)
    throw std::invalid_argument("svg: content.scenario is null (" + file + ")");
  const cspace::Scenario& scenario = *content.scenario;
  if (scenario.robot->dof() != 2) return false;
  const Point lo = scenario.robot->lowerLimits(), hi = scenario.robot->upperLimits();
  Canvas canvas(lo, hi);
  drawCObstacles(canvas, scenario, lo, hi);

  std::ostringstream subtitle;
  subtitle << "C-space of " << scenario.name;
  if (content.roadmap) {
    // Checked edges solid; lazy edges no query has checked (svmp.lazy) dashed.
    for (const bool checked : {true, false}) {
      canvas.out() << "<path fill=\"none\" stroke=\"#aaaaaa\" stroke-width=\"0.6\""
                   << (checked ? "" : " stroke-dasharray=\"2,2\"") << " d=\"";
      for (int i = 0; i < content.roadmap->numNodes(); ++i)
        for (const planners::Edge& edge : content.roadmap->neighbours(i))
          if (edge.to > i && edge.checked == checked)
            canvas.out() << 'M' << canvas.xy(content.roadmap->node(i)) << 'L'
                         << canvas.xy(content.roadmap->node(edge.to));
      canvas.out() << "\"/>\n";
    }
    subtitle << "; " << content.roadmap->numNodes() << " milestones, "
             << content.roadmap->numEdges() << " edges";
  }
  if (content.samples) {
    const planners::ObstacleSamples& samples = *content.samples;
    for (int i = 0; i < samples.size(); ++i)
      canvas.circle(samples.points.col(i), 1.8,
                    std::string("fill=\"") + classColour(samples.labels[i]) + "\"");
    for (int i = 0; i < samples.size(); ++i)
      if (samples.boundary[i])
        canvas.circle(samples.points.col(i), 3.6,
                      "fill=\"none\" stroke=\"black\" stroke-width=\"0.7\"");
    subtitle << "; " << samples.size() << " obstacle samples (" << samples.numBoundary()
             << " boundary)";
  }
  if (content.risk) {
    // Later classes thinner, so boundaries that coincide (two classes: F_2 = -F_1) all show.
    const int classes = content.risk->numClasses();
    for (int k = 0; k < classes; ++k)
      canvas.out() << "<path fill=\"none\" stroke=\"" << classColour(content.risk->classes()[k])
                   << "\" stroke-width=\""
                   << svgNumber(1.2 + 2.0 * (classes - 1 - k) / std::max(classes - 1, 1))
                   << "\" stroke-linecap=\"round\" d=\""
                   << zeroLevelSetPath(canvas, *content.risk, k, lo, hi) << "\"/>\n";
    subtitle << "; lines: F_k = 0";
  }
  if (content.roadmap)
    for (const Eigen::VectorXd& q : content.roadmap->nodes())
      canvas.circle(q, 2.2, "fill=\"black\"");
  drawPathAndEnds(canvas, content);
  writeFileAtomically(file, canvas.document(content.title, subtitle.str(),
                                   obstacleLegend(*scenario.environment), "q1", "q2"));
  return true;
}

bool writeWorkspaceSvg(const std::string& file, const SvgContent& content, int snapshots) {
  if (!content.scenario)
    throw std::invalid_argument("svg: content.scenario is null (" + file + ")");
  const cspace::Scenario& scenario = *content.scenario;
  const robots::Robot& robot = *scenario.robot;
  if (robot.workspaceDim() != 2) return false;
  const bool point_robot = dynamic_cast<const robots::PointRobot*>(&robot) != nullptr;

  // Poses to draw, in drawing order: intermediate (light), goal (dashed grey), start (solid black).
  std::vector<std::pair<Eigen::VectorXd, std::string>> poses;
  Polygon tip_trace;
  Eigen::VectorXd start, goal;
  const bool has_ends = endpoints(content, start, goal);
  const bool has_path = content.path && content.path->size() > 1;
  if (!point_robot && has_path) {
    const std::vector<Eigen::VectorXd>& path = *content.path;
    const cspace::ConfigurationSpace space = scenario.makeSpace();
    std::vector<double> cumulative{0};
    for (size_t i = 1; i < path.size(); ++i)
      cumulative.push_back(cumulative.back() + space.distance(path[i - 1], path[i]));
    const int n = std::max(snapshots, 2);
    for (int i = 1; i + 1 < n; ++i)
      poses.emplace_back(
          pointAlong(path, cumulative, cumulative.back() * i / (n - 1)),
          "fill=\"#9ecae1\" fill-opacity=\"0.3\" stroke=\"#6baed6\" stroke-width=\"0.8\"");
    Eigen::Matrix3Xd tip;
    for (int i = 0; i <= 400; ++i) {
      robot.controlPoints(pointAlong(path, cumulative, cumulative.back() * i / 400), tip);
      tip_trace.push_back(tip.col(tip.cols() - 1).head<2>());
    }
  }
  if (!point_robot && has_ends) {
    poses.emplace_back(
        goal, "fill=\"none\" stroke=\"#808080\" stroke-width=\"1.5\" stroke-dasharray=\"5,3\"");
    poses.emplace_back(start, "fill=\"none\" stroke=\"black\" stroke-width=\"1.6\"");
  }

  // Bounds: obstacles and what is drawn of the robot (point robots: their joint limits).
  std::vector<Polygon> obstacle_outlines;
  for (const cspace::Obstacle& o : scenario.environment->obstacles())
    obstacle_outlines.push_back(planners::projectedOutline(o.shape, o.shape.pose, kArcPoints));
  Point lo = Point::Constant(1e300), hi = Point::Constant(-1e300);
  for (const Polygon& outline : obstacle_outlines) extend(lo, hi, outline);
  std::vector<std::vector<Polygon>> pose_outlines;
  for (const auto& [q, style] : poses) {
    pose_outlines.push_back(planners::robotOutlines(robot, q, kArcPoints));
    for (const Polygon& outline : pose_outlines.back()) extend(lo, hi, outline);
  }
  extend(lo, hi, tip_trace);
  if (point_robot) extend(lo, hi, {robot.lowerLimits(), robot.upperLimits()});
  if (!(lo.x() < hi.x() && lo.y() < hi.y())) lo = hi - Point::Ones();
  const Point margin = 0.04 * (hi - lo);
  Canvas canvas(lo - margin, hi + margin);

  for (size_t i = 0; i < obstacle_outlines.size(); ++i) {
    const cspace::Obstacle& o = scenario.environment->obstacles()[i];
    canvas.polyline(obstacle_outlines[i],
                    std::string("fill=\"") + classColour(o.id) + "\" stroke=\"" +
                        classColour(o.id) + "\" " +
                        (o.is_virtual ? "fill-opacity=\"0.08\" stroke-dasharray=\"6,4\""
                                      : "fill-opacity=\"0.45\""),
                    true);
  }
  if (!tip_trace.empty())
    canvas.polyline(tip_trace, std::string("fill=\"none\" stroke=\"") + kPathColour +
                                   "\" stroke-width=\"1\" stroke-dasharray=\"3,2\"");
  for (size_t i = 0; i < poses.size(); ++i)
    for (const Polygon& outline : pose_outlines[i]) canvas.polyline(outline, poses[i].second, true);
  if (point_robot) drawPathAndEnds(canvas, content);

  std::string subtitle = "workspace of " + scenario.name;
  if (!point_robot && has_path)
    subtitle +=
        "; " + std::to_string(poses.size()) + " poses along the path (start solid, goal dashed)";
  writeFileAtomically(file, canvas.document(content.title, subtitle, obstacleLegend(*scenario.environment),
                                   "x", "y"));
  return true;
}

}  // namespace svmp::experiments
