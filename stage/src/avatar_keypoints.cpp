#include "freeplay/stage/avatar_keypoints.hpp"

#include <fmt/format.h>

#include <cmath>

#include "freeplay/core/error.hpp"
#include "raw_mujoco.hpp"

namespace freeplay::stage {

namespace {

Eigen::Vector3d body_position(const mjData* d, int body) {
  return {d->xpos[3 * body], d->xpos[3 * body + 1], d->xpos[3 * body + 2]};
}

Eigen::Matrix3d body_rotation(const mjData* d, int body) {
  Eigen::Matrix3d r;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) r(i, j) = d->xmat[9 * body + 3 * i + j];
  }
  return r;
}

int body_id(const mjModel* m, const std::string& name) {
  const int id = mj_name2id(m, mjOBJ_BODY, name.c_str());
  if (id < 0) throw InputError(fmt::format("the stage has no avatar body '{}'", name), "avatar");
  return id;
}

/// The two ends of a capsule geom (its `fromto`: from, to), in the world frame; MuJoCo points the geom's z axis
/// from `to` towards `from`.
std::pair<Eigen::Vector3d, Eigen::Vector3d> capsule_ends(const mjModel* m, const mjData* d, int geom) {
  const Eigen::Vector3d c(d->geom_xpos[3 * geom], d->geom_xpos[3 * geom + 1], d->geom_xpos[3 * geom + 2]);
  const Eigen::Vector3d z(d->geom_xmat[9 * geom + 2], d->geom_xmat[9 * geom + 5], d->geom_xmat[9 * geom + 8]);
  const double half = m->geom_size[3 * geom + 1];
  return {c + half * z, c - half * z};
}

std::array<Eigen::Vector2d, kFacePoints> make_face_template() {
  std::array<Eigen::Vector2d, kFacePoints> t;
  int k = 0;
  for (int i = 0; i <= 16; ++i) {  // jaw: ear to ear under the chin
    const double a = M_PI * (0.05 + 0.9 * i / 16.0);
    t[k++] = {-0.72 * std::cos(a), 0.05 - 0.72 * std::sin(a)};
  }
  for (int side = 0; side < 2; ++side) {  // eyebrows 17–21 (right), 22–26 (left)
    for (int i = 0; i < 5; ++i) {
      const double u = (side == 0 ? -1.0 : 1.0) * (0.62 - 0.11 * (side == 0 ? i : 4 - i));
      t[k++] = {u, 0.42 + 0.05 * std::sin(M_PI * i / 4.0)};
    }
  }
  for (int i = 0; i < 4; ++i) t[k++] = {0.0, 0.30 - 0.12 * i};   // nose bridge 27–30
  for (int i = 0; i < 5; ++i) t[k++] = {-0.16 + 0.08 * i, -0.12};  // nostrils 31–35
  for (int side = 0; side < 2; ++side) {  // eyes 36–41 (right), 42–47 (left): corners and lids
    const double cu = side == 0 ? -0.35 : 0.35;
    const double cv = 0.25;
    for (int i = 0; i < 6; ++i) {
      const double a = M_PI * i / 3.0;
      t[k++] = {cu + (side == 0 ? -1.0 : 1.0) * -0.14 * std::cos(a), cv + 0.05 * std::sin(a)};
    }
  }
  for (int i = 0; i < 12; ++i) {  // outer lip 48–59
    const double a = 2.0 * M_PI * i / 12.0;
    t[k++] = {-0.30 * std::cos(a), -0.42 + 0.10 * std::sin(a)};
  }
  for (int i = 0; i < 8; ++i) {  // inner lip 60–67
    const double a = 2.0 * M_PI * i / 8.0;
    t[k++] = {-0.20 * std::cos(a), -0.42 + 0.04 * std::sin(a)};
  }
  t[k++] = {-0.35, 0.25};  // pupils 68 (right), 69 (left)
  t[k++] = {0.35, 0.25};
  return t;
}

}  // namespace

const std::array<Eigen::Vector2d, kFacePoints>& face_template() {
  static const auto t = make_face_template();
  return t;
}

AvatarKeypoints avatar_keypoints(const Stage& stage, ChildRole role) {
  const auto& index = stage.model().avatar(role);
  if (!index.present) {
    throw InputError(fmt::format("the scene has no {} child", child_role_name(role)), "avatar", "a child's seat");
  }
  const mjModel* m = raw_model(stage.model());
  const mjData* d = raw_data(stage);
  const std::string p(child_role_name(role));
  AvatarKeypoints k;
  auto body = [&](CocoPoint point) -> Eigen::Vector3d& { return k.body[static_cast<std::size_t>(point)]; };

  // Head: the face sphere (the head body's first geom) and the eyes site; x forward, y to the child's left, z up.
  const int head = body_id(m, p + "_head");
  const int face_geom = m->body_geomadr[head];
  const Eigen::Vector3d centre(d->geom_xpos[3 * face_geom], d->geom_xpos[3 * face_geom + 1],
                               d->geom_xpos[3 * face_geom + 2]);
  const double radius = m->geom_size[3 * face_geom];
  const Eigen::Matrix3d R = body_rotation(d, head);
  const Eigen::Vector3d forward = R.col(0), left = R.col(1), up = R.col(2);
  auto on_face = [&](double u, double v) {  // a point of the face disc on the sphere's front
    const double s = 0.75;                  // the face covers the front three quarters of the head's radius
    const double w = std::sqrt(std::max(0.0, 1.0 - s * s * (u * u + v * v)));
    return Eigen::Vector3d(centre + radius * (w * forward + s * u * left + s * v * up));
  };
  const auto& tmpl = face_template();
  for (int i = 0; i < kFacePoints; ++i) k.face[static_cast<std::size_t>(i)] = on_face(tmpl[i].x(), tmpl[i].y());
  body(CocoPoint::nose) = k.face[30];
  body(CocoPoint::r_eye) = k.face[68];
  body(CocoPoint::l_eye) = k.face[69];
  body(CocoPoint::r_ear) = centre - radius * left;
  body(CocoPoint::l_ear) = centre + radius * left;
  body(CocoPoint::neck) = body_position(d, head);

  // Arms: the shoulder and elbow joints are the body origins; the wrist is the end of the forearm capsule.
  for (int side = 0; side < 2; ++side) {
    const std::string s = side == 0 ? "r" : "l";
    const int upper = body_id(m, p + "_" + s + "_upper_arm");
    const int fore = body_id(m, p + "_" + s + "_forearm");
    const auto [elbow, wrist] = capsule_ends(m, d, m->body_geomadr[fore]);
    body(side == 0 ? CocoPoint::r_shoulder : CocoPoint::l_shoulder) = body_position(d, upper);
    body(side == 0 ? CocoPoint::r_elbow : CocoPoint::l_elbow) = elbow;
    body(side == 0 ? CocoPoint::r_wrist : CocoPoint::l_wrist) = wrist;
    // Hand: wrist, then four points along each finger from the palm to the fingertip site, fanned across the palm.
    const Eigen::Vector3d tip = stage.site_position(index.hand_tip_site[static_cast<std::size_t>(side)]);
    const Eigen::Matrix3d F = body_rotation(d, fore);
    const double breadth = m->geom_size[3 * (m->body_geomadr[fore] + 1) + 1];  // the hand ellipsoid's half width
    auto& hand = k.hands[static_cast<std::size_t>(side)];
    hand[0] = wrist;
    for (int finger = 0; finger < 5; ++finger) {
      const double across = (finger - 2) / 2.0 * breadth * (side == 0 ? 1.0 : -1.0);
      for (int j = 1; j <= 4; ++j) {
        const double along = 0.4 + 0.15 * j;
        hand[static_cast<std::size_t>(1 + 4 * finger + j - 1)] =
            wrist + along * (tip - wrist) + across * (1.0 - 0.1 * j) * F.col(1);
      }
    }
  }

  // Legs: the pelvis body's first four geoms are the thighs and shins (right side first), as the stage builds them.
  const int pelvis = body_id(m, p + "_pelvis");
  for (int side = 0; side < 2; ++side) {
    const int thigh = m->body_geomadr[pelvis] + 2 * side;
    const auto [hip, knee] = capsule_ends(m, d, thigh);
    const auto ankle = capsule_ends(m, d, thigh + 1).second;
    body(side == 0 ? CocoPoint::r_hip : CocoPoint::l_hip) = hip;
    body(side == 0 ? CocoPoint::r_knee : CocoPoint::l_knee) = knee;
    body(side == 0 ? CocoPoint::r_ankle : CocoPoint::l_ankle) = ankle;
  }
  return k;
}

}  // namespace freeplay::stage
