#include "bench/experiments/fastron/cspace_picture.hpp"

#include <cmath>
#include <iomanip>
#include <numbers>
#include <sstream>

#include "bench/experiments/atomic_file.hpp"
#include "bench/experiments/output_text.hpp"
#include "cspace/collision_checker.hpp"
#include "robots/planar_arm.hpp"

namespace svmp::experiments::fastron {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr int kGrid = 120;
constexpr double kPanel = 300;  // px per panel side

// One C-space panel: cells coloured by `colliding`, support points (joints 1, 2) as dots.
void panel(std::ostringstream& svg, double x0, const std::string& title, const std::vector<bool>& colliding,
           const std::vector<Eigen::VectorXd>& support) {
  const double cell = kPanel / kGrid;
  svg << "<g transform=\"translate(" << svgNumber(x0) << ",40)\"><text x=\"0\" y=\"-8\" font-size=\"14\">" << title << "</text>\n";
  svg << "<rect width=\"" << kPanel << "\" height=\"" << kPanel << "\" fill=\"#ffffff\" stroke=\"#000\"/>\n";
  // One rectangle per run of colliding cells in a grid column.
  for (int i = 0; i < kGrid; ++i)
    for (int j = 0; j < kGrid;) {
      if (!colliding[i * kGrid + j]) {
        ++j;
        continue;
      }
      int end = j;
      while (end < kGrid && colliding[i * kGrid + end]) ++end;
      svg << "<rect x=\"" << svgNumber(i * cell) << "\" y=\"" << svgNumber(kPanel - end * cell) << "\" width=\"" << svgNumber(cell + 0.2)
          << "\" height=\"" << svgNumber((end - j) * cell + 0.2) << "\" fill=\"#d9534f\"/>\n";
      j = end;
    }
  for (const auto& q : support) {
    if (std::abs(q[2]) > 0.3) continue;  // near the slice q3 = 0
    svg << "<circle cx=\"" << svgNumber((q[0] + kPi) / (2 * kPi) * kPanel) << "\" cy=\"" << svgNumber(kPanel - (q[1] + kPi) / (2 * kPi) * kPanel)
        << "\" r=\"2\" fill=\"#1f4e9c\"/>\n";
  }
  svg << "<text x=\"0\" y=\"" << kPanel + 16 << "\" font-size=\"11\">q1 in [-pi, pi] (right), q2 in [-pi, pi] (up), q3 = 0</text></g>\n";
}

}  // namespace

PictureResult drawCspacePicture(const std::string& dir, std::uint64_t seed, const cspace::FastronCheckerOptions& fk_in,
                                const cspace::FastronCheckerOptions& rbf_in) {
  const Eigen::Vector3d lo(-kPi, -kPi, -kPi), hi(kPi, kPi, kPi);
  auto arm = std::make_shared<const robots::PlanarArm>(std::vector<double>{0.4, 0.3, 0.2},
                                                        std::vector<double>{0.04, 0.04, 0.04}, lo, hi);
  std::vector<cspace::Obstacle> obstacles;
  const std::vector<Eigen::Vector3d> centres = {{0.45, 0.35, 0}, {-0.4, 0.45, 0}, {0.1, -0.55, 0}};
  for (size_t i = 0; i < centres.size(); ++i) {
    cspace::Obstacle o;
    o.name = "cube_" + std::to_string(i + 1);
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = centres[i];
    o.shape = robots::Shape::box(Eigen::Vector3d(0.15, 0.15, 0.15), pose);
    obstacles.push_back(o);
  }
  auto env = std::make_shared<const cspace::Environment>(obstacles);
  const cspace::CollisionChecker exact(arm, env, false);
  cspace::FastronCheckerOptions fk = fk_in, rbf = rbf_in;
  fk.initial_samples = rbf.initial_samples = 2000;  // the same labelled configurations for both
  cspace::FastronChecker fk_model(arm, fk), rbf_model(arm, rbf);
  fk_model.train(exact, seed);
  rbf_model.train(exact, seed);

  std::vector<bool> truth(kGrid * kGrid), by_fk(kGrid * kGrid), by_rbf(kGrid * kGrid);
  int fk_agree = 0, rbf_agree = 0;
  for (int i = 0; i < kGrid; ++i)
    for (int j = 0; j < kGrid; ++j) {
      const Eigen::Vector3d q(-kPi + (i + 0.5) * 2 * kPi / kGrid, -kPi + (j + 0.5) * 2 * kPi / kGrid, 0);
      const int k = i * kGrid + j;
      truth[k] = !exact.isValid(q);
      by_fk[k] = !fk_model.isValid(q);
      by_rbf[k] = !rbf_model.isValid(q);
      fk_agree += truth[k] == by_fk[k];
      rbf_agree += truth[k] == by_rbf[k];
    }
  PictureResult r;
  r.grid = kGrid;
  r.fk_support = fk_model.model().size();
  r.rbf_support = rbf_model.model().size();
  r.fk_accuracy = double(fk_agree) / (kGrid * kGrid);
  r.rbf_accuracy = double(rbf_agree) / (kGrid * kGrid);

  std::ostringstream svg;
  const double width = 4 * (kPanel + 30) + 20;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << svgNumber(width) << "\" height=\"" << svgNumber(kPanel + 80)
      << "\" font-family=\"sans-serif\">\n<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>\n";
  // (a) workspace: the arm at q = 0 and the cubes, 1 m = kPanel / 2 px, base at the panel centre.
  const double s = kPanel / 2.2;
  auto px = [&](double x) { return svgNumber(10 + kPanel / 2 + s * x); };
  auto py = [&](double y) { return svgNumber(40 + kPanel / 2 - s * y); };
  svg << "<text x=\"10\" y=\"32\" font-size=\"14\">(a) workspace, arm at q = 0</text>\n<rect x=\"10\" y=\"40\" width=\"" << kPanel
      << "\" height=\"" << kPanel << "\" fill=\"none\" stroke=\"#000\"/>\n";
  for (const auto& c : centres)
    svg << "<rect x=\"" << px(c.x() - 0.075) << "\" y=\"" << py(c.y() + 0.075) << "\" width=\"" << svgNumber(0.15 * s)
        << "\" height=\"" << svgNumber(0.15 * s) << "\" fill=\"#d9534f\"/>\n";
  Eigen::Matrix3Xd points;
  arm->controlPoints(Eigen::Vector3d::Zero(), points);
  std::string prev_x = px(0), prev_y = py(0);
  for (int c = 0; c < points.cols(); ++c) {
    svg << "<line x1=\"" << prev_x << "\" y1=\"" << prev_y << "\" x2=\"" << px(points(0, c)) << "\" y2=\"" << py(points(1, c))
        << "\" stroke=\"#333\" stroke-width=\"5\"/>\n";
    prev_x = px(points(0, c)), prev_y = py(points(1, c));
  }
  panel(svg, 10 + (kPanel + 30), "(b) ground truth (FCL)", truth, {});
  panel(svg, 10 + 2 * (kPanel + 30),
        "(c) Fastron RBF: " + std::to_string(r.rbf_support) + " support points, " + svgNumber(100 * r.rbf_accuracy) + "%",
        by_rbf, rbf_model.supportConfigurations());
  panel(svg, 10 + 3 * (kPanel + 30),
        "(d) Fastron FK: " + std::to_string(r.fk_support) + " support points, " + svgNumber(100 * r.fk_accuracy) + "%",
        by_fk, fk_model.supportConfigurations());
  svg << "</svg>\n";
  r.file = dir + "/fastron_fig1_cspace.svg";
  writeFileAtomically(r.file, svg.str());
  return r;
}

}  // namespace svmp::experiments::fastron
