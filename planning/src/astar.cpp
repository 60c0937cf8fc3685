#include "freeplay/planning/astar.hpp"

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <algorithm>
#include <functional>

#include <fmt/format.h>

#include "freeplay/core/error.hpp"
#include "path_metrics.hpp"

namespace freeplay::planning {

namespace {

constexpr std::array<std::array<int, 2>, 8> kNeighbours = {
    {{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, 1}, {1, -1}, {-1, 1}, {-1, -1}}};

// 16 bytes: a search pushes at most 8 entries per cell, and the area is checked to keep that within 32 bits.
struct OpenEntry {
  double f;
  std::uint32_t order;  // insertion order: a deterministic tie-break
  std::uint32_t node;
  bool operator>(const OpenEntry& other) const {
    return f != other.f ? f > other.f : order > other.order;
  }
};

// What a search knows of one cell; valid only while `search` is the current search's number.
struct NodeState {
  double g;          // cost of the best path found to the cell
  double step_cost;  // the cost of entering the cell (computed on first touch)
  std::size_t parent;
  std::uint32_t search;
  bool closed;
};

// A search's per-cell records and open list, kept between searches on one thread: a new search only bumps the
// search number (a record from an earlier search reads as untouched), so nothing is cleared or allocated.
struct SearchWorkspace {
  std::vector<NodeState> nodes;
  std::vector<OpenEntry> open;
  std::uint32_t search = 0;
  void begin(std::size_t count) {
    if (nodes.size() != count || search == std::numeric_limits<std::uint32_t>::max()) {
      nodes.assign(count, NodeState{0.0, 0.0, 0, 0, false});
      search = 0;
    }
    ++search;
    open.clear();
  }
};

double heuristic_cells(AStarHeuristic heuristic, int dcol, int drow) {
  const int ax = std::abs(dcol);
  const int ay = std::abs(drow);
  return heuristic == AStarHeuristic::Manhattan ? ax + ay : std::max(ax, ay);
}

}  // namespace

GridSearchResult astar_search(const OccupancyGrid& grid, const Cell& start, const Cell& goal,
                              AStarHeuristic heuristic, int outside_margin_cells, double time_budget_s) {
  const double budget = std::max(0.0, time_budget_s) * kAStarExpansionsPerBudgetSecond;
  const auto max_expansions = budget >= 1.8e19 ? std::numeric_limits<std::uint64_t>::max()
                                               : static_cast<std::uint64_t>(budget);
  const int margin = std::max(0, outside_margin_cells);
  const int width = OccupancyGrid::kCols + 2 * margin;
  const int height = OccupancyGrid::kRows + 2 * margin;
  const auto inside = [&](const Cell& c) {
    return c.col >= -margin && c.col < OccupancyGrid::kCols + margin && c.row >= -margin &&
           c.row < OccupancyGrid::kRows + margin;
  };
  if (!inside(start) || !inside(goal)) {
    throw InputError(fmt::format("start or goal cell lies more than {} cells outside the map", margin),
                     "start/goal", "points within the screen plus the outside margin");
  }
  // The searched area with a one-cell ring of closed cells around it, so that a neighbour needs no bounds check.
  const int stride = width + 2;
  const std::size_t count = static_cast<std::size_t>(stride) * static_cast<std::size_t>(height + 2);
  const auto node_of = [&](const Cell& c) {
    return static_cast<std::size_t>(c.row + margin + 1) * static_cast<std::size_t>(stride) +
           static_cast<std::size_t>(c.col + margin + 1);
  };
  const auto cell_of_node = [&](std::size_t node) {
    // Nodes and the stride fit 32 bits (checked below): a 32-bit division is several times quicker than a 64-bit one.
    const auto small = static_cast<std::uint32_t>(node);
    const auto row_length = static_cast<std::uint32_t>(stride);
    return Cell{static_cast<int>(small % row_length) - margin - 1, static_cast<int>(small / row_length) - margin - 1};
  };
  if (count >= std::numeric_limits<std::uint32_t>::max() / 9) {
    throw InputError(fmt::format("an outside margin of {} cells makes the search area too large", margin),
                     "outside_margin_cells", "a margin that keeps the area under 4.7e8 cells");
  }
  constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
  // One workspace per thread, reused by every search on it (no allocation after the first).
  thread_local SearchWorkspace work;
  work.begin(count);
  const auto touch = [&](std::size_t node) -> NodeState& {
    NodeState& state = work.nodes[node];
    if (state.search != work.search) {
      state = NodeState{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN(), kNone,
                        work.search, false};
    }
    return state;
  };
  for (int col = 0; col < stride; ++col) {
    touch(static_cast<std::size_t>(col)).closed = true;
    touch(count - 1 - static_cast<std::size_t>(col)).closed = true;
  }
  for (int row = 0; row < height + 2; ++row) {
    touch(static_cast<std::size_t>(row) * static_cast<std::size_t>(stride)).closed = true;
    touch(static_cast<std::size_t>(row) * static_cast<std::size_t>(stride) + static_cast<std::size_t>(stride - 1))
        .closed = true;
  }
  // The open list is a binary heap kept by push_heap/pop_heap, as std::priority_queue keeps it.
  std::vector<OpenEntry>& open = work.open;
  const auto push = [&open](const OpenEntry& entry) {
    open.push_back(entry);
    std::push_heap(open.begin(), open.end(), std::greater<>{});
  };

  GridSearchResult result;
  std::uint32_t order = 0;
  const std::size_t start_node = node_of(start);
  const std::size_t goal_node = node_of(goal);
  touch(start_node).g = 0.0;
  push({heuristic_cells(heuristic, goal.col - start.col, goal.row - start.row), order++,
        static_cast<std::uint32_t>(start_node)});
  const std::array<std::ptrdiff_t, 8> offsets = [&] {
    std::array<std::ptrdiff_t, 8> out{};
    for (std::size_t i = 0; i < kNeighbours.size(); ++i) out[i] = kNeighbours[i][1] * stride + kNeighbours[i][0];
    return out;
  }();

  while (!open.empty()) {
    std::pop_heap(open.begin(), open.end(), std::greater<>{});
    const OpenEntry top = open.back();
    open.pop_back();
    NodeState& here_state = work.nodes[top.node];  // touched when it was pushed
    if (here_state.closed) continue;
    here_state.closed = true;
    ++result.expanded;
    if (top.node == goal_node) break;
    if (result.expanded > max_expansions) {
      result.timed_out = true;
      return result;
    }
    const double here_g = here_state.g;
    const Cell here = cell_of_node(top.node);
    for (std::size_t i = 0; i < offsets.size(); ++i) {
      const std::size_t next_node = static_cast<std::size_t>(static_cast<std::ptrdiff_t>(top.node) + offsets[i]);
      NodeState& next_state = touch(next_node);
      if (next_state.closed) continue;
      const Cell next{here.col + kNeighbours[i][0], here.row + kNeighbours[i][1]};
      if (std::isnan(next_state.step_cost)) next_state.step_cost = grid.step_cost(next);
      const double candidate = here_g + next_state.step_cost;
      if (candidate < next_state.g) {
        next_state.g = candidate;
        next_state.parent = top.node;
        push({candidate + heuristic_cells(heuristic, goal.col - next.col, goal.row - next.row), order++,
              static_cast<std::uint32_t>(next_node)});
      }
    }
  }
  if (!touch(goal_node).closed) return result;

  result.found = true;
  result.cost = work.nodes[goal_node].g;
  for (std::size_t node = goal_node; node != kNone; node = work.nodes[node].parent) {
    result.cells.push_back(cell_of_node(node));
  }
  std::reverse(result.cells.begin(), result.cells.end());
  return result;
}

PlanResult AStarPlanner::plan(const PlanRequest& request, Rng& rng) const {
  validate_request(request);
  static_cast<void>(rng());  // every planner draws one value, so the stream does not depend on the choice
  const auto started = std::chrono::steady_clock::now();
  const auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  };

  const OccupancyGrid grid = OccupancyGrid::build(request.obstacles, request.item);
  if (auto rejected = detail::check_goal(request, grid, options_)) {
    rejected->metrics.planning_time_s = elapsed();
    return *rejected;
  }
  const GridSearchResult search =
      astar_search(grid, OccupancyGrid::cell_of(request.start), OccupancyGrid::cell_of(request.goal),
                   options_.heuristic, options_.outside_margin_cells, request.time_budget_s);
  PlanResult result;
  result.metrics.expanded_nodes = search.expanded;
  if (!search.found) {
    result = detail::failure(search.timed_out ? FailureReason::TimeBudgetExceeded : FailureReason::NoPath,
                             search.timed_out ? fmt::format("A* ran out of its {} s budget", request.time_budget_s)
                                              : std::string("A* found no path"));
    result.metrics.expanded_nodes = search.expanded;
    result.metrics.planning_time_s = elapsed();
    return result;
  }
  result.ok = true;
  result.path.reserve(search.cells.size());
  for (std::size_t i = 0; i < search.cells.size(); ++i) {
    result.path.push_back({static_cast<double>(i) * options_.pose_period_s, OccupancyGrid::cell_point(search.cells[i])});
  }
  result.metrics.path_cost = search.cost;
  result.metrics.planning_time_s = elapsed();
  detail::measure_path(request, result);
  return result;
}

}  // namespace freeplay::planning
