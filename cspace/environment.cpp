#include "cspace/environment.hpp"

#include <cmath>
#include <stdexcept>

namespace svmp::cspace {

Environment::Environment(std::vector<Obstacle> obstacles) : obstacles_(std::move(obstacles)) {
  for (size_t i = 0; i < obstacles_.size(); ++i) {
    Obstacle& o = obstacles_[i];
    o.id = static_cast<int>(i) + 1;
    if (o.name.empty()) o.name = "obstacle" + std::to_string(o.id);
    const std::string err = o.shape.validate();
    if (!err.empty()) throw std::invalid_argument("obstacle '" + o.name + "': " + err);
    if (!std::isfinite(o.weight) || !(o.weight > 0))
      throw std::invalid_argument("obstacle '" + o.name + "': weight must be positive, got " +
                                  std::to_string(o.weight));
  }
}

const Obstacle& Environment::byId(int id) const {
  if (id < 1 || id > size()) throw std::out_of_range("no obstacle with id " + std::to_string(id));
  return obstacles_[id - 1];
}

int Environment::numReal() const {
  int n = 0;
  for (const auto& o : obstacles_) n += !o.is_virtual;
  return n;
}

}  // namespace svmp::cspace
