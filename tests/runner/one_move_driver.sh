#!/usr/bin/env bash
# Every front moves an item through the one move driver (runner/move_driver.hpp): outside the planning library
# (the executor itself) and the driver, no source streams, starts or cancels a move executor; a driver is owned only
# by the robot side (runner/robot_side.hpp: the in-process episode and the action sources in front of it, the web
# page's wizard and SPARC modes and `freeplay serve --robot external`), controller scenarios and `freeplay plan`, so
# the live fronts (ros/, web/) hear a move through a MoveObserver instead of driving one; and no source builds a
# policy Observation's items but the episode's robot view (runner/src/sim_world_robot.cpp) and the live robot node,
# whose observation comes from the ROS graph (ros/src/robot_node.cpp).
# Usage: one_move_driver.sh SOURCE_DIR
set -uo pipefail
cd "$1" || exit 2
dirs=(agents analysis cli core localisation policies python recording results ros runner scenario sim stage web)
status=0
drivers=$(grep -rn -E 'MoveOutputs|executor_?(->|\.)(start|step|cancel)\(' --include='*.cpp' --include='*.hpp' \
  "${dirs[@]}" | grep -v '^runner/src/move_driver\.cpp:')
if [ -n "$drivers" ]; then
  echo "a move executor driven outside runner/src/move_driver.cpp (use runner::MoveDriver):"
  echo "$drivers"
  status=1
fi
owners=$(grep -rn -w 'MoveDriver' --include='*.cpp' --include='*.hpp' "${dirs[@]}" | grep -v -E \
  '^(runner/src/move_driver\.cpp|runner/include/freeplay/runner/(move_driver|robot_side)\.hpp|runner/src/controller_episode\.cpp|cli/cmd_plan\.cpp):')
if [ -n "$owners" ]; then
  echo "a move driver owned outside the robot side, controller scenarios and freeplay plan (act through RobotSide):"
  echo "$owners"
  status=1
fi
builders=$(grep -rn -E 'ItemObservation [a-z_]+[;{]|ItemObservation obs' --include='*.cpp' --include='*.hpp' \
  "${dirs[@]}" | grep -v -E '^(runner/src/sim_world_robot\.cpp|ros/src/robot_node\.cpp|policies/)')
if [ -n "$builders" ]; then
  echo "a policy Observation built outside the episode's robot view (runner/src/sim_world_robot.cpp):"
  echo "$builders"
  status=1
fi
[ $status -eq 0 ] && echo "one move driver, one observation builder"
exit $status
