#!/usr/bin/env python3
"""Writes assets/nao/nao.xml: a primitive-shape MJCF model of the NAO H25 V5.

Every number comes from /work/shared/reference/nao-and-setup.md (section numbers quoted below): joint
origins, axes and ranges (§1.4), link masses / centres of mass / inertias about the COM (§1.6, right side
mirrored), camera poses and field of view (§1.8), actuator gains (§1.10) and primitive sizes (§1.11).
Run `python3 assets/nao/make_nao.py` after changing a number; the output is committed.
"""
import math
import pathlib

# --- §1.6 inertial data of the left side and the unpaired links (mass kg, COM m, Ixx Iyy Izz Ixy Ixz Iyz) ---
INERTIA = {
    "torso": (1.04956, (-0.00413, 0, 0.04342), (3.084e-3, 2.884e-3, 1.592e-3, 1.431e-5, -3.302e-5, -2.708e-5)),
    "Neck": (0.07842, (-1e-5, 0, -0.02742), (1.603e-5, 1.704e-5, 5.534e-6, 1.6e-9, 3.2e-9, -5.30e-8)),
    "Head": (0.60533, (-0.00112, 0, 0.05258), (9.578e-4, 8.168e-4, 9.850e-4, 8.788e-6, 5.337e-6, -2.996e-5)),
    "Shoulder": (0.09304, (-0.00165, -0.02663, 0.00014), (1.830e-5, 1.390e-5, 2.019e-5, 2.060e-6, 1.9e-9, -3.666e-7)),
    "Bicep": (0.15777, (0.02455, 0.00563, 0.0033), (8.718e-5, 2.747e-4, 2.418e-4, -2.534e-5, -1.421e-5, 4.714e-7)),
    "Elbow": (0.06483, (-0.02744, 0, -0.00014), (5.596e-6, 2.662e-5, 2.763e-5, 4.2e-9, 2.922e-7, -1.8e-9)),
    "ForeArm": (0.07761, (0.02556, 0.00281, 0.00076), (2.467e-5, 3.838e-5, 3.597e-5, 3.232e-6, 1.582e-6, 1.392e-7)),
    "wrist": (0.18533, (0.03434, -0.00088, 0.00308), (6.865e-5, 1.358e-4, 1.332e-4, 1.155e-7, -2.873e-6, 2.675e-6)),
    "gripper": (2e-6, (0, 0, 0), (1.1e-9, 1.1e-9, 1.1e-9, 0, 0, 0)),
    "Pelvis": (0.06981, (-0.00781, -0.01114, 0.02661), (2.341e-5, 4.764e-5, 4.970e-5, 1.079e-6, -1.760e-6, 2.761e-6)),
    "Hip": (0.14053, (-0.01549, 0.00029, -0.00515), (2.384e-5, 6.082e-5, 5.437e-5, -6.536e-7, 7.129e-6, -2.141e-7)),
    "Thigh": (0.38968, (0.00138, 0.00221, -0.05373), (5.098e-4, 4.654e-4, 3.011e-4, 2.113e-6, 5.641e-5, -7.910e-6)),
    "Tibia": (0.30142, (0.00453, 0.00225, -0.04936), (4.462e-4, 3.881e-4, 1.855e-4, 3.706e-6, -3.090e-5, 6.020e-6)),
    "AnklePitch": (0.13416, (0.00045, 0.00029, 0.00685), (3.220e-5, 6.794e-5, 5.483e-5, -8.8e-9, 4.275e-6, 2.848e-7)),
    "ankle": (0.17184, (0.02542, 0.0033, -0.03239), (8.729e-5, 3.530e-4, 4.128e-4, 8.719e-6, -2.106e-6, 3.735e-7)),
}

# --- §1.4 joint ranges (rad) ---
RANGE = {
    "HeadYaw": (-2.0857, 2.0857), "HeadPitch": (-0.6720, 0.5149),
    "LShoulderPitch": (-2.0857, 2.0857), "LShoulderRoll": (-0.3142, 1.3265), "LElbowYaw": (-2.0857, 2.0857),
    "LElbowRoll": (-1.5446, -0.0349), "LWristYaw": (-1.8238, 1.8238), "LHand": (0.0, 1.0),
    "RShoulderPitch": (-2.0857, 2.0857), "RShoulderRoll": (-1.3265, 0.3142), "RElbowYaw": (-2.0857, 2.0857),
    "RElbowRoll": (0.0349, 1.5446), "RWristYaw": (-1.8238, 1.8238), "RHand": (0.0, 1.0),
    "LHipYawPitch": (-1.145303, 0.740810), "LHipRoll": (-0.379472, 0.790477), "LHipPitch": (-1.535889, 0.484090),
    "LKneePitch": (-0.092346, 2.112528), "LAnklePitch": (-1.189516, 0.922747), "LAnkleRoll": (-0.397880, 0.769001),
    "RHipYawPitch": (-1.145303, 0.740810), "RHipRoll": (-0.790477, 0.379472), "RHipPitch": (-1.535889, 0.484090),
    "RKneePitch": (-0.103083, 2.120198), "RAnklePitch": (-1.186448, 0.932056), "RAnkleRoll": (-0.768992, 0.397935),
}

WHITE = "shell"
GREY = "joint"


def fmt(*values):
    return " ".join(f"{v:.6g}" for v in values)


def inertial(key, mirror):
    mass, com, (ixx, iyy, izz, ixy, ixz, iyz) = INERTIA[key]
    x, y, z = com
    if mirror:  # right side = left side mirrored in y (§1.6)
        y, ixy, iyz = -y, -ixy, -iyz
    return f'<inertial pos="{fmt(x, y, z)}" mass="{mass:.6g}" fullinertia="{fmt(ixx, iyy, izz, ixy, ixz, iyz)}"/>'


def joint(name, axis):
    lo, hi = RANGE[name]
    return f'<joint name="{name}" axis="{fmt(*axis)}" range="{fmt(lo, hi)}"/>'


def arm(side):
    s = 1 if side == "L" else -1
    lower = side.lower()
    mirror = side == "R"
    fingers = "\n".join(
        f'              <geom name="{lower}_finger{i}" type="capsule" size="0.0055" material="{GREY}" '
        f'fromto="0 {fmt(s * dy)} 0 {fmt(0.045 * math.cos(1.0), s * dy, -0.045 * math.sin(1.0))}"/>'
        for i, dy in ((1, 0.01157), (2, -0.01157)))
    return f"""
      <body name="{side}Shoulder" pos="0 {fmt(s * 0.098)} 0.1">
        {inertial("Shoulder", mirror)}
        {joint(side + "ShoulderPitch", (0, 1, 0))}
        <geom name="{lower}_shoulder" type="sphere" size="0.034" pos="0 {fmt(s * 0.01)} 0" material="{WHITE}"/>
        <body name="{side}Bicep">
          {inertial("Bicep", mirror)}
          {joint(side + "ShoulderRoll", (0, 0, 1))}
          <geom name="{lower}_upper_arm" type="capsule" size="0.025" fromto="0.02 {fmt(s * 0.005)} 0 0.09 {fmt(s * 0.015)} 0" material="{WHITE}"/>
          <body name="{side}Elbow" pos="0.105 {fmt(s * 0.015)} 0">
            {inertial("Elbow", mirror)}
            {joint(side + "ElbowYaw", (1, 0, 0))}
            <body name="{side}ForeArm">
              {inertial("ForeArm", mirror)}
              {joint(side + "ElbowRoll", (0, 0, 1))}
              <geom name="{lower}_elbow" type="sphere" size="0.024" material="{GREY}"/>
              <geom name="{lower}_forearm" type="capsule" size="0.0225" fromto="0.01 0 0 0.05 0 0" material="{WHITE}"/>
              <body name="{lower}_wrist" pos="0.05595 0 0">
                {inertial("wrist", mirror)}
                {joint(side + "WristYaw", (1, 0, 0))}
                <geom name="{lower}_palm" type="box" size="0.028 0.022 0.016" pos="0.032 0 -0.006" material="{WHITE}"/>
                <geom name="{lower}_thumb" type="capsule" size="0.0055" fromto="0.045 0 -0.024 0.07 0 -0.03" material="{GREY}"/>
                <site name="{lower}_fingertip" pos="0.112 0 -0.012" size="0.004" rgba="1 0.3 0 1"/>
                <body name="{lower}_gripper" pos="0.05775 0 -0.01231">
                  {inertial("gripper", mirror)}
                  {joint(side + "Hand", (0, -1, 0))}
{fingers}
                </body>
              </body>
            </body>
          </body>
        </body>
      </body>"""


def leg(side):
    s = 1 if side == "L" else -1
    lower = side.lower()
    mirror = side == "R"
    hyp_axis = (0, 0.7071068, -0.7071068) if side == "L" else (0, 0.7071068, 0.7071068)
    return f"""
      <body name="{side}Pelvis" pos="0 {fmt(s * 0.05)} -0.085">
        {inertial("Pelvis", mirror)}
        {joint(side + "HipYawPitch", hyp_axis)}
        <body name="{side}Hip">
          {inertial("Hip", mirror)}
          {joint(side + "HipRoll", (1, 0, 0))}
          <body name="{side}Thigh">
            {inertial("Thigh", mirror)}
            {joint(side + "HipPitch", (0, 1, 0))}
            <geom name="{lower}_thigh" type="capsule" size="0.035" fromto="0 0 -0.005 0 0 -0.09" material="{WHITE}"/>
            <body name="{side}Tibia" pos="0 0 -0.1">
              {inertial("Tibia", mirror)}
              {joint(side + "KneePitch", (0, 1, 0))}
              <geom name="{lower}_tibia" type="capsule" size="0.03" fromto="0 0 0 0 0 -0.09" material="{WHITE}"/>
              <body name="{side}AnklePitch" pos="0 0 -0.1029">
                {inertial("AnklePitch", mirror)}
                {joint(side + "AnklePitch", (0, 1, 0))}
                <body name="{lower}_ankle">
                  {inertial("ankle", mirror)}
                  {joint(side + "AnkleRoll", (1, 0, 0))}
                  <geom name="{lower}_ankle_shell" type="sphere" size="0.03" pos="0 0 -0.012" material="{WHITE}"/>
                  <geom name="{lower}_foot" type="box" size="0.08 0.045 0.01" pos="0.03 {fmt(s * 0.003)} -0.03511" material="{WHITE}"/>
                  <site name="{lower}_sole" pos="0 0 -0.04511" size="0.005"/>
                </body>
              </body>
            </body>
          </body>
        </body>
      </body>"""


def camera(name, pos, pitch_down, fovy_deg):
    # MJCF cameras look along -z with +y up: x_cam = -y_link, y_cam = z_link of the pitched link (§1.8).
    s, c = math.sin(pitch_down), math.cos(pitch_down)
    return (f'<camera name="{name}" pos="{fmt(*pos)}" xyaxes="0 -1 0 {fmt(s, 0, c)}" fovy="{fovy_deg}"/>')


def main():
    actuated = [n for n in RANGE if n != "RHipYawPitch"]
    actuators = "\n".join(
        f'    <position name="{n}" class="nao" joint="{n}" ctrlrange="{fmt(*RANGE[n])}"/>' for n in actuated)
    xml = f"""<!-- NAO H25 V5 from primitives. GENERATED by assets/nao/make_nao.py from the numbers of
     nao-and-setup.md (§1.4 joints, §1.6 inertias, §1.8 cameras, §1.10 gains); edit the script, not this file.
     Torso is a mocap body (the robot stands still; its pose is set by the stage), zero pose puts the soles at z = 0. -->
<mujoco model="nao_h25_v5">
  <compiler angle="radian" inertiafromgeom="false"/>
  <option timestep="0.002"/>
  <default>
    <default class="nao">
      <joint limited="true" damping="1.084" armature="0.045" frictionloss="0.03"/>
      <geom contype="0" conaffinity="0" group="1"/>
      <site group="3"/>
      <position kp="21.1" ctrllimited="true" forcelimited="true" forcerange="-5 5"/>
    </default>
  </default>
  <asset>
    <material name="{WHITE}" rgba="0.93 0.93 0.9 1" specular="0.4" shininess="0.5"/>
    <material name="{GREY}" rgba="0.35 0.36 0.38 1"/>
    <material name="eye" rgba="0.2 0.55 1 1" emission="0.6"/>
  </asset>
  <worldbody>
    <body name="torso" childclass="nao" pos="0 0 0.33301" mocap="true">
      {inertial("torso", False)}
      <geom name="torso_shell" type="box" size="0.05 0.07 0.075" pos="0 0 0.045" material="{WHITE}"/>
      <geom name="pelvis_shell" type="capsule" size="0.035" fromto="0 -0.045 -0.055 0 0.045 -0.055" material="{GREY}"/>
      <geom name="chest_button" type="cylinder" size="0.012 0.003" pos="0.05 0 0.055" zaxis="1 0 0" material="{GREY}"/>
      <body name="Neck" pos="0 0 0.1265">
        {inertial("Neck", False)}
        {joint("HeadYaw", (0, 0, 1))}
        <geom name="neck" type="cylinder" size="0.018 0.015" pos="0 0 -0.01" material="{GREY}"/>
        <body name="Head">
          {inertial("Head", False)}
          {joint("HeadPitch", (0, 1, 0))}
          <geom name="head" type="sphere" size="0.056" pos="0 0 0.05" material="{WHITE}"/>
          <geom name="left_eye" type="cylinder" size="0.011 0.003" pos="0.047 0.026 0.045" zaxis="0.9 0.4 0" material="eye"/>
          <geom name="right_eye" type="cylinder" size="0.011 0.003" pos="0.047 -0.026 0.045" zaxis="0.9 -0.4 0" material="eye"/>
          <geom name="left_ear" type="cylinder" size="0.02 0.006" pos="0 0.055 0.048" zaxis="0 1 0" material="{GREY}"/>
          <geom name="right_ear" type="cylinder" size="0.02 0.006" pos="0 -0.055 0.048" zaxis="0 1 0" material="{GREY}"/>
          <site name="head_top" pos="0.001 0 0.1099" size="0.004"/>
          <site name="gaze" pos="0.05871 0 0.06364" size="0.004"/>
          {camera("CameraTop", (0.05871, 0, 0.06364), 0.0209, 47.6)}
          {camera("CameraBottom", (0.05071, 0, 0.01774), 0.6929, 47.6)}
        </body>
      </body>{arm("L")}{arm("R")}{leg("L")}{leg("R")}
    </body>
  </worldbody>
  <equality>
    <joint name="hip_yaw_pitch_coupling" joint1="RHipYawPitch" joint2="LHipYawPitch" polycoef="0 1 0 0 0"/>
  </equality>
  <actuator>
{actuators}
  </actuator>
</mujoco>
"""
    out = pathlib.Path(__file__).with_name("nao.xml")
    out.write_text(xml)
    print(f"wrote {out} ({len(actuated)} actuators)")


if __name__ == "__main__":
    main()
