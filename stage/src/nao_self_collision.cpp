#include "freeplay/stage/nao_self_collision.hpp"

#include <fmt/format.h>
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <limits>

#include "freeplay/stage/nao_description.hpp"
#include "freeplay/stage/stage_state.hpp"
#include "raw_mujoco.hpp"

namespace freeplay::stage {

namespace {

// Smallest signed distance between two geoms (m; negative = penetration), +inf when far apart.
double penetration(const mjModel* m, const mjData* d, int g1, int g2) {
  const Eigen::Map<const Eigen::Vector3d> p1(d->geom_xpos + 3 * g1);
  const Eigen::Map<const Eigen::Vector3d> p2(d->geom_xpos + 3 * g2);
  if ((p1 - p2).norm() > m->geom_rbound[g1] + m->geom_rbound[g2] + 0.01) return std::numeric_limits<double>::infinity();
  int a = g1;
  int b = g2;
  if (m->geom_type[a] > m->geom_type[b]) std::swap(a, b);
  const mjfCollision collide = mjCOLLISIONFUNC[m->geom_type[a]][m->geom_type[b]];
  if (collide == nullptr) return std::numeric_limits<double>::infinity();
  std::array<mjContact, mjMAXCONPAIR> contacts{};
  const int n = collide(m, d, contacts.data(), a, b, 0.0);
  double smallest = std::numeric_limits<double>::infinity();
  for (int i = 0; i < n; ++i) smallest = std::min(smallest, contacts[static_cast<std::size_t>(i)].dist);
  return smallest;
}

}  // namespace

NaoSelfCollision::NaoSelfCollision(const StageModel& model, double penetration_m)
    : model_(&model), penetration_m_(penetration_m) {
  const mjModel* m = raw_model(model);
  const NaoIndex& nao = model.nao();
  std::vector<int> geoms;
  for (int g = 0; g < m->ngeom; ++g) {
    if (m->body_rootid[m->geom_bodyid[g]] == nao.torso_body) geoms.push_back(g);
  }
  const auto geom_parent = [m](int body) {
    int b = m->body_parentid[body];
    while (b > 0 && m->body_geomnum[b] == 0) b = m->body_parentid[b];
    return b;
  };
  mjData* scratch = mj_makeData(m);
  const auto& zero = posture_angles(NaoPosture::StandZero);
  for (int j = 0; j < kNaoJointCount; ++j) {
    const int joint = nao.joint[static_cast<std::size_t>(j)];
    scratch->qpos[nao.qpos[static_cast<std::size_t>(j)]] =
        std::clamp(zero[static_cast<std::size_t>(j)], m->jnt_range[2 * joint], m->jnt_range[2 * joint + 1]);
  }
  mj_kinematics(m, scratch);
  for (std::size_t a = 0; a < geoms.size(); ++a) {
    for (std::size_t b = a + 1; b < geoms.size(); ++b) {
      const int ba = m->geom_bodyid[geoms[a]];
      const int bb = m->geom_bodyid[geoms[b]];
      if (ba == bb || geom_parent(ba) == bb || geom_parent(bb) == ba) continue;
      if (penetration(m, scratch, geoms[a], geoms[b]) < 0.0) continue;  // overlapping in StandZero: structural
      pairs_.push_back({geoms[a], geoms[b]});
    }
  }
  mj_deleteData(scratch);
  colliding_.assign(pairs_.size(), false);
}

int NaoSelfCollision::update(const Stage& stage, bool& any) {
  const mjModel* m = raw_model(*model_);
  int onsets = 0;
  any = false;
  for (std::size_t i = 0; i < pairs_.size(); ++i) {
    const bool now = penetration(m, raw_data(stage), pairs_[i].first, pairs_[i].second) < -penetration_m_;
    if (now && !colliding_[i]) {
      ++onsets;
      const std::string a = geom_name(*model_, pairs_[i].first);
      const std::string b = geom_name(*model_, pairs_[i].second);
      hit_.insert(fmt::format("{}/{}", a.empty() ? "?" : a, b.empty() ? "?" : b));
    }
    colliding_[i] = now;
    any = any || now;
  }
  return onsets;
}

}  // namespace freeplay::stage
