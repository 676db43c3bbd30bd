#pragma once
// Das & Yip 2019, Fig 1: a 3-DoF arm among cube obstacles; its C-space slice (joints 1 and 2, joint 3
// at zero) as ground truth from the exact checker on a grid, beside Fastron RBF and Fastron FK trained
// on the same labelled configurations, with the support points that lie near the slice. One SVG with
// three panels (and the workspace), written whole or not at all.
#include <string>

#include "cspace/fastron_checker.hpp"

namespace svmp::experiments::fastron {

struct PictureResult {
  std::string file;
  int grid = 0;
  int fk_support = 0, rbf_support = 0;
  double fk_accuracy = 0, rbf_accuracy = 0;  // agreement with the ground truth on the slice
};

// Model options: gamma, beta and limits of `fk` and `rbf`; sample counts are the picture's own.
PictureResult drawCspacePicture(const std::string& dir, std::uint64_t seed, const cspace::FastronCheckerOptions& fk,
                                const cspace::FastronCheckerOptions& rbf);

}  // namespace svmp::experiments::fastron
