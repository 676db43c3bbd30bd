#include "planners/ompl/scenario_setup.hpp"

#include <ompl/base/ScopedState.h>

#include <stdexcept>
#include <string>

namespace svmp::ompl_planners {

ScenarioWorld::ScenarioWorld(cspace::Scenario scenario, int threads)
    : scenario_(std::move(scenario)), setup_(scenario_, threads) {}

std::shared_ptr<const ScenarioWorld> ScenarioWorld::make(cspace::Scenario scenario, int threads) {
  return std::shared_ptr<const ScenarioWorld>(new ScenarioWorld(std::move(scenario), threads));
}

ob::SpaceInformationPtr ScenarioWorld::spaceInformation() const {
  return makeSpaceInformation(setup_.planning, shared_from_this());
}

std::shared_ptr<og::SimpleSetup> ScenarioWorld::simpleSetup(int query) const {
  if (query < 0 || query >= static_cast<int>(scenario_.queries.size()))
    throw std::out_of_range(scenario_.path + ": no query " + std::to_string(query));
  auto setup = std::make_shared<og::SimpleSetup>(spaceInformation());
  const Eigen::VectorXd& scale = setup_.space.metricScale();
  ob::ScopedState<> start(setup->getStateSpace()), goal(setup->getStateSpace());
  toState(scenario_.queries[query].start, scale, start.get());
  toState(scenario_.queries[query].goal, scale, goal.get());
  setup->setStartAndGoalStates(start, goal);
  return setup;
}

}  // namespace svmp::ompl_planners
