// nanoflann dataset adaptor over the columns of a matrix (one point per column), shared by the k-d
// trees of the truncated evaluator, the roadmap's nearest neighbours and the class colouring. The
// matrix must outlive the tree built on it.
#pragma once

#include <Eigen/Core>
#include <cstddef>

namespace svmp::svm {

struct ColumnCloud {
  const Eigen::MatrixXd* points;
  size_t kdtree_get_point_count() const { return static_cast<size_t>(points->cols()); }
  double kdtree_get_pt(size_t i, size_t k) const {
    return (*points)(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(i));
  }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;  // nanoflann computes the bounding box
  }
};

}  // namespace svmp::svm
