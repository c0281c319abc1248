// A world as one tile of a run cut by space (docs/decisions/0012-partitioned-runs.md, "Robots in
// the first tile"): the home of every robot, or ghosts of them moved by the home's courses.
#include "agents/robot_agent.hpp"
#include "agents/world.hpp"

namespace masnet::agents {

void World::home_robots(bool here) {
  MASNET_ASSERT(actuation_delay_.count() > 0, "robots in one tile act after a delay");
  radio_.home_mobiles(here);
  robots_here_ = here;
  keeps_courses_ = here;
}

void World::keep_course(std::size_t robot, std::uint32_t generation, sim::Time when,
                        const Vec2& target) {
  course_outbox_.push_back(Course{when, simulator_.peek_key(when),
                                  static_cast<std::uint32_t>(robot), generation, target.x(),
                                  target.y()});
}

void World::take_course(const Course& course) {
  MASNET_ASSERT(!robots_here_ && course.robot < robots_.size(), "a course of a ghost robot");
  RobotAgent* agent = robots_[course.robot].get();
  const std::uint32_t generation = course.generation;
  const double x = course.x, y = course.y;
  simulator_.at_keyed(course.when, course.key, sim::origin_of(robot_node(course.robot)),
                      [agent, generation, x, y] {
                        if (agent->generation() == generation) agent->steer(Vec2{x, y});
                      });
}

}  // namespace masnet::agents
