// The grid and the A* planner: faithful to the real map_and_plan, with the row offset fixed.

#include <gtest/gtest.h>

#include <cstdlib>
#include <functional>
#include <limits>
#include <map>
#include <queue>
#include <set>
#include <tuple>
#include <utility>
#include <vector>

#include "freeplay/planning/astar.hpp"
#include "freeplay/planning/layout.hpp"
#include "freeplay/planning/occupancy_grid.hpp"
#include "test_helpers.hpp"

namespace freeplay::planning {
namespace {

using testing::box;

PlanRequest request_between(Vec2 start, Vec2 goal, std::vector<Obstacle> obstacles) {
  PlanRequest request;
  request.item = "mover";
  request.start = start;
  request.goal = goal;
  request.obstacles = std::move(obstacles);
  return request;
}

// Plain Dijkstra over the same bounded cell graph (independent of the A* code).
double dijkstra_cost(const OccupancyGrid& grid, Cell start, Cell goal, int margin) {
  const auto inside = [&](const Cell& c) {
    return c.col >= -margin && c.col < OccupancyGrid::kCols + margin && c.row >= -margin &&
           c.row < OccupancyGrid::kRows + margin;
  };
  const auto key = [](const Cell& c) { return std::pair{c.col, c.row}; };
  std::map<std::pair<int, int>, double> dist;
  std::set<std::pair<double, std::pair<int, int>>> open;
  dist[key(start)] = 0.0;
  open.insert({0.0, key(start)});
  while (!open.empty()) {
    const auto [d, k] = *open.begin();
    open.erase(open.begin());
    if (k == key(goal)) return d;
    for (int dr = -1; dr <= 1; ++dr) {
      for (int dc = -1; dc <= 1; ++dc) {
        if (dr == 0 && dc == 0) continue;
        const Cell next{k.first + dc, k.second + dr};
        if (!inside(next)) continue;
        const double candidate = d + grid.step_cost(next);
        auto it = dist.find(key(next));
        if (it == dist.end() || candidate < it->second) {
          if (it != dist.end()) open.erase({it->second, key(next)});
          dist[key(next)] = candidate;
          open.insert({candidate, key(next)});
        }
      }
    }
  }
  return std::numeric_limits<double>::infinity();
}

TEST(OccupancyGrid, HasTheRealDimensionsAndCellMapping) {
  EXPECT_EQ(OccupancyGrid::kCols, 120);
  EXPECT_EQ(OccupancyGrid::kRows, 67);
  EXPECT_EQ(OccupancyGrid::cell_of({0.3, -0.1}), (Cell{60, 20}));
  EXPECT_EQ(OccupancyGrid::cell_of({0.0024, -0.0001}), (Cell{0, 0}));
  EXPECT_EQ(OccupancyGrid::cell_of({-0.001, 0.001}), (Cell{-1, -1}));
  const Vec2 p = OccupancyGrid::cell_point({7, 3});
  EXPECT_DOUBLE_EQ(p.x(), 0.035);
  EXPECT_DOUBLE_EQ(p.y(), -0.015);
  const OccupancyGrid empty;
  EXPECT_EQ(empty.occupancy({0, 0}), 0);
  EXPECT_EQ(empty.occupancy({119, 66}), 0);
}

TEST(OccupancyGrid, RasterisesBlursAndInhibitsTheMovedItem) {
  const std::vector<Obstacle> obstacles = {box("wall", 0.1, 0.2, -0.2, -0.1), box("mover", 0.3, 0.4, -0.2, -0.1)};
  const OccupancyGrid grid = OccupancyGrid::build(obstacles, "mover");
  EXPECT_EQ(grid.occupancy({30, 30}), 100);  // inside the wall
  EXPECT_EQ(grid.occupancy({70, 30}), 0);    // inside the inhibited item: ignored
  EXPECT_EQ(grid.occupancy({5, 5}), 0);
  // Column 41 lies just right of the wall (cols 20…40): a third of its 3 × 3 neighbourhood is covered.
  EXPECT_EQ(grid.occupancy({41, 30}), 34);
  EXPECT_EQ(grid.occupancy({40, 30}), 67);
  EXPECT_EQ(grid.occupancy({42, 30}), 0);
}

TEST(OccupancyGrid, FootprintTouchingRowZeroIsReadAtTheRightRow) {
  // Rows 0…2 covered; the real code read row (height − y) of the flipped map, i.e. one row off (§8.5).
  const OccupancyGrid grid = OccupancyGrid::build({box("top", 0.25, 0.30, -0.0125, 0.0)}, "");
  EXPECT_EQ(grid.occupancy({55, 0}), 100);
  EXPECT_EQ(grid.occupancy({55, 1}), 100);
  EXPECT_EQ(grid.occupancy({55, 2}), 67);
  EXPECT_EQ(grid.occupancy({55, 3}), 34);
  EXPECT_EQ(grid.occupancy({55, 4}), 0);
  // Same at the bottom edge: rows 64…66.
  const OccupancyGrid bottom = OccupancyGrid::build({box("bottom", 0.25, 0.30, -0.335, -0.32)}, "");
  EXPECT_EQ(bottom.occupancy({55, 66}), 100);
  EXPECT_EQ(bottom.occupancy({55, 63}), 34);
  EXPECT_EQ(bottom.occupancy({55, 62}), 0);
}

TEST(OccupancyGrid, OutsideCostIsNearestEdgeCostPlusTenPerCell) {
  OccupancyGrid grid;
  grid.set_occupancy({0, 10}, 40);
  EXPECT_DOUBLE_EQ(grid.step_cost({0, 10}), 41.0);
  EXPECT_DOUBLE_EQ(grid.step_cost({-3, 10}), 41.0 + 30.0);
  EXPECT_DOUBLE_EQ(grid.step_cost({-3, -4}), 1.0 + 50.0);  // nearest edge cell (0, 0) is free; distance 5 cells
}

TEST(AStar, StraightMoveIsHandCheckable) {
  const AStarPlanner planner;
  Rng rng(1);
  const PlanResult result = planner.plan(request_between({0.1, -0.1}, {0.12, -0.1}, {}), rng);
  ASSERT_TRUE(result.ok) << result.message;
  ASSERT_EQ(result.path.size(), 5U);
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_DOUBLE_EQ(result.path[i].t, 0.1 * static_cast<double>(i));
    EXPECT_NEAR(result.path[i].position.x(), 0.1 + 0.005 * static_cast<double>(i), 1e-12);
    EXPECT_NEAR(result.path[i].position.y(), -0.1, 1e-12);
  }
  EXPECT_DOUBLE_EQ(result.metrics.path_cost, 4.0);
  EXPECT_NEAR(result.metrics.path_length_m, 0.02, 1e-12);
  EXPECT_GT(result.metrics.expanded_nodes, 0U);
}

TEST(AStar, DiagonalStepsCostTheSameAsStraightOnes) {
  const AStarPlanner planner;
  Rng rng(1);
  const PlanResult result = planner.plan(request_between({0.1, -0.1}, {0.115, -0.115}, {}), rng);
  ASSERT_TRUE(result.ok);
  ASSERT_EQ(result.path.size(), 4U);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(OccupancyGrid::cell_of(result.path[i].position + Vec2(1e-6, -1e-6)),
              (Cell{20 + static_cast<int>(i), 20 + static_cast<int>(i)}));
  }
  EXPECT_DOUBLE_EQ(result.metrics.path_cost, 3.0);
}

// A wall across the whole screen (and beyond it) with one 3.5 cm gap.
std::vector<Obstacle> wall_with_gap() {
  return {box("upper", 0.2525, 0.2675, -0.1525, 0.1), box("lower", 0.2525, 0.2675, -0.5, -0.1875)};
}

TEST(AStar, CrossesAWallThroughItsGap) {
  const AStarPlanner planner;
  Rng rng(3);
  const auto obstacles = wall_with_gap();
  const PlanResult result = planner.plan(request_between({0.1, -0.05}, {0.4, -0.05}, obstacles), rng);
  ASSERT_TRUE(result.ok);
  bool crossed = false;
  for (const auto& pose : result.path) {
    for (const auto& obstacle : obstacles) EXPECT_FALSE(point_in_polygon(obstacle.footprint, pose.position));
    if (pose.position.x() > 0.2525 && pose.position.x() < 0.2675) {
      crossed = true;
      EXPECT_GT(pose.position.y(), -0.1875);
      EXPECT_LT(pose.position.y(), -0.1525);
    }
  }
  EXPECT_TRUE(crossed);
  EXPECT_GT(result.metrics.min_clearance_m, 0.0);
}

// A wall with no free gap: two blocks (rows <= 28 and >= 30) leave row 29 uncovered; the blur makes it 67.
std::vector<Obstacle> wall_with_blurred_seam() {
  return {box("upper", 0.2525, 0.2725, -0.1425, 0.1), box("lower", 0.2525, 0.2725, -0.5, -0.1525)};
}

TEST(AStar, UnavoidableCrossingTakesTheCheapestSeamAndMatchesDijkstra) {
  const auto obstacles = wall_with_blurred_seam();
  const OccupancyGrid grid = OccupancyGrid::build(obstacles, "");
  EXPECT_EQ(grid.occupancy({53, 29}), 67);   // the seam row and its two neighbours (2/3 covered)
  EXPECT_EQ(grid.occupancy({53, 28}), 67);
  EXPECT_EQ(grid.occupancy({53, 20}), 100);  // solid wall
  const Cell start = OccupancyGrid::cell_of({0.1, -0.05});
  const Cell goal = OccupancyGrid::cell_of({0.4, -0.05});
  const double best = dijkstra_cost(grid, start, goal, 20);
  for (const auto heuristic : {AStarHeuristic::Manhattan, AStarHeuristic::Chebyshev}) {
    const GridSearchResult search = astar_search(grid, start, goal, heuristic, 20, 10.0);
    ASSERT_TRUE(search.found);
    EXPECT_DOUBLE_EQ(search.cost, best);
    bool through_seam = false;
    for (const auto& c : search.cells) {
      if (c.col >= 50 && c.col <= 54) {
        EXPECT_LE(grid.occupancy(c), 67) << "left the seam inside the wall at column " << c.col;
        through_seam = true;
      }
    }
    EXPECT_TRUE(through_seam);
  }
}

/// A random layout of 10 items (seeded), its grid without the first item, and a search from that item to a random goal.
struct RandomSearch {
  OccupancyGrid grid;
  Cell start;
  Cell goal;
};
RandomSearch random_search(std::uint64_t seed) {
  Rng rng(seed);
  const Layout layout = random_layout(approximate_item_shapes(), 10, rng);
  RandomSearch out{OccupancyGrid::build(layout.obstacles(), layout.items[0].name),
                   OccupancyGrid::cell_of({layout.items[0].pose.x, layout.items[0].pose.y}), {}};
  out.goal = OccupancyGrid::cell_of({rng.uniform(0.0, 0.528), rng.uniform(-0.335, 0.0)});
  return out;
}

TEST(AStar, AdmissibleHeuristicMatchesDijkstraOnRandomLayouts) {
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const auto [grid, start, goal] = random_search(seed);
    const GridSearchResult search = astar_search(grid, start, goal, AStarHeuristic::Chebyshev, 20, 10.0);
    ASSERT_TRUE(search.found);
    EXPECT_DOUBLE_EQ(search.cost, dijkstra_cost(grid, start, goal, 20)) << "seed " << seed;
    // The faithful Manhattan heuristic is never cheaper than the optimum.
    EXPECT_GE(astar_search(grid, start, goal, AStarHeuristic::Manhattan, 20, 10.0).cost, search.cost);
  }
}

// The search as the real planner's priority queue runs it (std::priority_queue on f, ties by insertion order), cell by
// cell, independent of the A* code's open list: its path and number of expansions.
std::pair<std::vector<Cell>, std::uint64_t> reference_astar(const OccupancyGrid& grid, Cell start, Cell goal,
                                                            AStarHeuristic heuristic, int margin) {
  const auto inside = [&](const Cell& c) {
    return c.col >= -margin && c.col < OccupancyGrid::kCols + margin && c.row >= -margin &&
           c.row < OccupancyGrid::kRows + margin;
  };
  const auto h = [&](const Cell& c) {
    const int dx = std::abs(goal.col - c.col), dy = std::abs(goal.row - c.row);
    return heuristic == AStarHeuristic::Manhattan ? dx + dy : std::max(dx, dy);
  };
  using Key = std::pair<int, int>;
  std::map<Key, double> g;
  std::map<Key, Key> parent;
  std::set<Key> closed;
  using Entry = std::tuple<double, std::uint64_t, Key>;  // f, insertion order, cell
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
  std::uint64_t order = 0, expanded = 0;
  g[{start.col, start.row}] = 0.0;
  open.emplace(h(start), order++, Key{start.col, start.row});
  while (!open.empty()) {
    const auto [f, o, here] = open.top();
    open.pop();
    if (!closed.insert(here).second) continue;
    ++expanded;
    if (here == Key{goal.col, goal.row}) break;
    // The real planner's neighbour order: the four sides, then the four diagonals.
    for (const auto& [dc, dr] : {Key{1, 0}, Key{-1, 0}, Key{0, 1}, Key{0, -1}, Key{1, 1}, Key{1, -1}, Key{-1, 1},
                                Key{-1, -1}}) {
      const Cell next{here.first + dc, here.second + dr};
      const Key k{next.col, next.row};
      if (!inside(next) || closed.contains(k)) continue;
      const double candidate = g[here] + grid.step_cost(next);
      if (!g.contains(k) || candidate < g[k]) {
        g[k] = candidate;
        parent[k] = here;
        open.emplace(candidate + h(next), order++, k);
      }
    }
  }
  std::vector<Cell> cells;
  for (Key k{goal.col, goal.row};; k = parent.at(k)) {
    cells.insert(cells.begin(), Cell{k.first, k.second});
    if (k == Key{start.col, start.row}) break;
  }
  return {cells, expanded};
}

// The open list pops exactly what the real planner's priority queue pops: the same path and the same expansions,
// ties included, with both heuristics (Manhattan is not consistent, so the popped f goes down as well as up).
TEST(AStar, ExpandsInThePriorityQueuesOrder) {
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const auto [grid, start, goal] = random_search(seed);
    for (const auto heuristic : {AStarHeuristic::Manhattan, AStarHeuristic::Chebyshev}) {
      const GridSearchResult search = astar_search(grid, start, goal, heuristic, 5, 10.0);
      const auto [cells, expanded] = reference_astar(grid, start, goal, heuristic, 5);
      ASSERT_TRUE(search.found);
      EXPECT_EQ(search.cells, cells) << "seed " << seed;
      EXPECT_EQ(search.expanded, expanded) << "seed " << seed;
    }
  }
}

TEST(AStar, GoalChecks) {
  const AStarPlanner planner;
  Rng rng(5);
  const std::vector<Obstacle> obstacles = {box("rock", 0.2, 0.3, -0.2, -0.1)};
  EXPECT_EQ(planner.plan(request_between({0.1, -0.05}, {0.25, -0.15}, obstacles), rng).reason,
            FailureReason::GoalInsideObstacle);
  EXPECT_EQ(planner.plan(request_between({0.1, -0.05}, {0.61, -0.15}, obstacles), rng).reason,
            FailureReason::GoalOffScreen);
  EXPECT_EQ(planner.plan(request_between({0.1, -0.05}, {0.3, 0.001}, obstacles), rng).reason,
            FailureReason::GoalOffScreen);
  // The edge of the rock (blurred rim) is not "inside": occupancy < 99.
  const PlanResult rim = planner.plan(request_between({0.1, -0.05}, {0.3025, -0.15}, obstacles), rng);
  EXPECT_TRUE(rim.ok) << rim.message;
}

// Four blocks enclosing a free pocket around (0.3, −0.17).
std::vector<Obstacle> ring_around_goal() {
  return {box("n", 0.25, 0.35, -0.14, -0.12), box("s", 0.25, 0.35, -0.22, -0.20), box("w", 0.25, 0.27, -0.22, -0.12),
          box("e", 0.33, 0.35, -0.22, -0.12)};
}

TEST(AStar, EnclosedGoalIsReachedAcrossTheRingAtACost) {
  const AStarPlanner planner;
  Rng rng(5);
  const PlanResult result = planner.plan(request_between({0.1, -0.05}, {0.3, -0.17}, ring_around_goal()), rng);
  ASSERT_TRUE(result.ok);  // A* is cost-based: it crosses an item when nothing else leads there
  EXPECT_GE(result.metrics.path_cost, 100.0);
  EXPECT_LT(result.metrics.min_clearance_m, 0.0);
}

TEST(AStar, StartOffTheMapIsAllowed) {
  const AStarPlanner planner;
  Rng rng(5);
  const PlanResult result = planner.plan(request_between({-0.02, 0.01}, {0.05, -0.05}, {}), rng);
  ASSERT_TRUE(result.ok);
  EXPECT_EQ(OccupancyGrid::cell_of(result.path.front().position + Vec2(1e-6, -1e-6)), (Cell{-4, -2}));
}

TEST(AStar, TinyBudgetOnALongSearchReportsTimeBudgetExceeded) {
  // The faithful heuristic is greedy, so force a long search with the admissible one on a blocked map.
  PlannerOptions options;
  options.heuristic = AStarHeuristic::Chebyshev;
  const AStarPlanner planner(options);
  Rng rng(5);
  PlanRequest request = request_between({0.1, -0.05}, {0.3, -0.17}, ring_around_goal());
  request.time_budget_s = 1e-9;
  const PlanResult result = planner.plan(request, rng);
  ASSERT_FALSE(result.ok);
  EXPECT_EQ(result.reason, FailureReason::TimeBudgetExceeded);
}

}  // namespace
}  // namespace freeplay::planning
