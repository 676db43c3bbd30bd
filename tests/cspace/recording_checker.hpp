#pragma once
// A validity checker that passes every check to another and keeps the configurations it was asked
// about, in order: tests of what a caller checks (the motion validator's order, Fastron's samples).
#include <cstdint>
#include <vector>

#include "cspace/validity_checker.hpp"

namespace svmp::cspace::test {

class RecordingChecker final : public ValidityChecker {
 public:
  explicit RecordingChecker(const ValidityChecker& inner) : inner_(inner) {}
  const robots::Robot& robot() const override { return inner_.robot(); }
  const Environment& environment() const override { return inner_.environment(); }
  int check(const Eigen::Ref<const Eigen::VectorXd>& q) const override {
    asked.push_back(q);
    return inner_.check(q);
  }
  int checkIncludingVirtual(const Eigen::Ref<const Eigen::VectorXd>& q) const override { return check(q); }
  bool hits(const Eigen::Ref<const Eigen::VectorXd>& q, int id) const override { return inner_.hits(q, id); }
  double clearance(const Eigen::Ref<const Eigen::VectorXd>& q) const override { return inner_.clearance(q); }
  bool checksSelfCollision() const override { return false; }
  std::uint64_t collisionChecks() const override { return asked.size(); }
  mutable std::vector<Eigen::VectorXd> asked;

 private:
  const ValidityChecker& inner_;
};

}  // namespace svmp::cspace::test
