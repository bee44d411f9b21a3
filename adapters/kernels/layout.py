"""The layouts of the flat buffers the kernels work on: the arm state, the controllers, the
sensing, the twin and its contact bodies, and the addresses into Pinocchio's and MuJoCo's data;
with the robot facts and the control period the compiled code is built with."""

from __future__ import annotations

from lightrocks.adapters.robots import common

ARM_DOF, NV = 7, 9
FINGER_TRAVEL, GRIPPER_BAND = 0.04, 0.002
"""The robot facts the compiled code uses, repeated here because the kernels' cache is keyed on
the kernel modules alone: a change in adapters.robots.common that is not made here too fails
at import instead of running stale cached code."""
if (ARM_DOF, NV, FINGER_TRAVEL, GRIPPER_BAND) != (
    common.ARM_DOF,
    common.NV,
    common.FINGER_TRAVEL,
    common.GRIPPER_BAND,
):
    raise ImportError(
        "adapters/kernels/layout.py must repeat the constants of adapters/robots/common.py"
    )

DT = 0.001
"""Control period [s]."""

# -- the arm state buffer (adapters.arm.ArmState.buffer) ----------------------------------------
STATE = 0
"""Joint positions (NV), then velocities (NV)."""
POS = STATE + 2 * NV
ROT = POS + 3
FT_POS = ROT + 9
FT_ROT = FT_POS + 3
TWIST = FT_ROT + 9
BIAS = TWIST + 6
JAC = BIAS + ARM_DOF
"""TCP Jacobian of the arm joints, 6 x ARM_DOF, row-major. Rotations are row-major too."""
MASS_INV = JAC + 6 * ARM_DOF
"""Inverse of the arm block of the mass matrix, refreshed every SLOW_EVERY ticks."""
MASS_DIAG = MASS_INV + ARM_DOF * ARM_DOF
"""Diagonal of the arm block of the mass matrix, refreshed with MASS_INV."""
TAU = MASS_DIAG + ARM_DOF
"""The controller's arm torques for the next step."""
TICKS = TAU + ARM_DOF
"""Reads of the plant's state so far: the mass terms are refreshed on every SLOW_EVERY-th,
starting with the first."""
SENSING = TICKS + 1
"""Start of the sensing block (offsets S_* below, relative to it)."""

# -- the Cartesian impedance buffer (adapters.control.CartesianImpedance) -------------------------
C_K = 0
C_D = C_K + 6
C_P0 = C_D + 6
C_DP = C_P0 + 3
C_DR = C_DP + 3
C_R0 = C_DR + 3
C_RGOAL = C_R0 + 9
C_PGOAL = C_RGOAL + 9
C_TWSET = C_PGOAL + 3
C_DURATION = C_TWSET + 6
C_ELAPSED = C_DURATION + 1
C_MOVING = C_ELAPSED + 1
C_OFFSET = C_MOVING + 1
"""1.0 when the task frame is not the TCP."""
C_TASK_R = C_OFFSET + 1
C_TASK_P = C_TASK_R + 9
C_NS_POSTURE = C_TASK_P + 3
C_NS_STATE = C_NS_POSTURE + ARM_DOF
"""Null-space torque = posture term + (ARM_DOF x 2 NV matrix) @ joint state."""
C_ERRORS = C_NS_STATE + ARM_DOF * 2 * NV
"""Rows: position error, linear and angular error velocity, world axes."""
C_LOCAL = C_ERRORS + 9
"""The rows of the errors in task axes."""
C_EROT = C_LOCAL + 9
C_FRAME_JAC = C_EROT + 3
C_FRAME_ROT = C_FRAME_JAC + 6 * ARM_DOF
C_FRAME_POS = C_FRAME_ROT + 9
C_FRAME_TWIST = C_FRAME_POS + 3
C_RATIO = C_FRAME_TWIST + 6
"""Damping ratios."""
C_POSTURE = C_RATIO + 6
"""Null-space posture: the arm configuration at command start."""
C_TICKS = C_POSTURE + ARM_DOF
"""Ticks run so far: the slow terms are refreshed on every SLOW_EVERY-th, starting with the
first."""
C_SCRATCH = C_TICKS + 1
"""Room for the intermediate results of a tick (no allocation per tick)."""
CARTESIAN_SIZE = C_SCRATCH + 48

SLOW_EVERY = 10
"""Ticks between refreshes of the mass matrix and of what the controllers derive from it, which
change slowly with the configuration."""
NULLSPACE_STIFFNESS = 10.0
"""Posture stiffness [Nm/rad] pulling the elbow towards the configuration at command start."""
NULLSPACE_DAMPING = 2.0
LAMBDA_REGULARISATION = 1e-6
"""Added to the diagonal of Λ⁻¹ before inverting it (near singular configurations)."""

# -- the joint impedance buffer (adapters.control.JointImpedance) -------------------------------
J_K = 0
J_RATIO = J_K + ARM_DOF
"""Damping ratios."""
J_Q0 = J_RATIO + ARM_DOF
J_DQ = J_Q0 + ARM_DOF
J_VSET = J_DQ + ARM_DOF
J_DURATION = J_VSET + ARM_DOF
J_ELAPSED = J_DURATION + 1
JOINT_SIZE = J_ELAPSED + 1

# -- the sensing buffer (adapters.sensing.WristSensor and the cell's motion sensors) ------------
S_RAW = 0
"""Raw wrist wrench (see adapters.sensing), input of each tick."""
S_OFFSET = S_RAW + 6
S_WEIGHT = S_OFFSET + 6
S_LOAD_COM = S_WEIGHT + 3
S_ALPHA = S_LOAD_COM + 3
S_VALUES = S_ALPHA + 1
"""Filtered wrench at the TCP, world axes."""
S_PEAK = S_VALUES + 6
S_TURNED = S_PEAK + 1
S_YAW = S_TURNED + 1
S_R0 = S_YAW + 1
"""TCP rotation at command start."""
S_SENSOR_ROT = S_R0 + 9
"""MuJoCo: the ft site's rotation when the step computed the force/torque sensors, whose
values are in that frame."""
SENSE_SIZE = S_SENSOR_ROT + 9
ARM_SIZE = SENSING + SENSE_SIZE

# -- the Pinocchio twin's buffer (adapters.pinocchio.plant.PinocchioPlant) -------------------------
T_DAMPING = 0
"""Minus the joint damping of the robot joints."""
T_LOAD = T_DAMPING + NV
T_LOAD_COM = T_LOAD + 3
"""Weight of the hand subtree [N] and its centre of mass in the ft frame."""
T_CONTACT = T_LOAD_COM + 3
"""Contact wrench on the hand subtree at the ft site, world axes."""
T_GENERALIZED = T_CONTACT + 6
"""Generalized forces of the robot joints."""
T_HAND = T_GENERALIZED + NV
"""Placement of the hand body in the frames' joint (see P_JOINT_ROT), as F_TCP."""
T_STIFFNESS = T_HAND + 12
"""Contacts: normal stiffness [N/m] and damping [N s/m] per point, Coulomb friction
coefficient, and the sliding speed [m/s] at which friction reaches its limit."""
T_CONTACT_DAMPING = T_STIFFNESS + 1
T_FRICTION = T_CONTACT_DAMPING + 1
T_SLIP = T_FRICTION + 1
T_LOW = T_SLIP + 1
"""Room for a step's Cholesky factor of the arm's mass matrix (ARM_DOF x ARM_DOF), its
accelerations, the placement of the hand or the ft site and that of a contact body (each as
F_TCP)."""
T_ACCELERATION = T_LOW + ARM_DOF * ARM_DOF
T_PLACEMENT = T_ACCELERATION + ARM_DOF
T_BODY = T_PLACEMENT + 12
T_TORQUE_LIMIT = T_BODY + 12
"""The arm motors' torque limits [Nm]: the twin clamps the controller's torques to them, as
MuJoCo clamps a motor's control to its range."""
T_BOXES = T_TORQUE_LIMIT + ARM_DOF
"""The static boxes, T_BOX values each (offsets BOX_*)."""
BOX_REACH = 0
"""The world-axis box (x, y, z low, then high) the hand origin must enter to touch the box."""
BOX_NEAR = BOX_REACH + 6
"""1.0 when the hand origin is in reach at this step."""
BOX_CENTRE = BOX_NEAR + 1
BOX_ROT = BOX_CENTRE + 3
"""The box's rotation, row-major."""
BOX_HALF = BOX_ROT + 9
"""Half sizes."""
T_BOX = BOX_HALF + 3
TWIN_SIZE = T_BOXES
"""Size of the buffer of a scene without static boxes; each box adds T_BOX."""

# -- the twin's contact bodies (adapters.pinocchio.plant.PinocchioPlant) ----------------------
B_ROT, B_POS, B_START, B_COUNT = range(4)
"""``links`` array, per body (hand, then the fingers): the addresses of the rotation
(column-major) and translation of ``data.oMi`` of its joint, and where its points start in
``bodies`` and how many there are."""
B_INTS = B_COUNT + 1
B_PLACEMENT = 0
"""``bodies`` array, per body: its placement in its joint (as F_TCP), then 1.0 for each joint
velocity that moves it; after all bodies, their points (x, y, z in the body frame)."""
B_SUPPORT = B_PLACEMENT + 12
B_HEADER = B_SUPPORT + NV

# -- Pinocchio's data (adapters.arm.PinocchioArm.index and .frames) -------------------------------
P_J, P_NLE, P_M, P_JOINT_ROT, P_JOINT_POS = range(5)
"""``index`` array: the addresses of Pinocchio's ``data.J`` (the joint Jacobians, 6 x NV, world
frame), ``data.nle``, ``data.M`` (upper triangle), all column-major, and of the rotation
(column-major) and translation of ``data.oMi`` of the joint that carries the TCP and ft frames
and the hand body."""
P_SIZE = P_JOINT_POS + 1
F_TCP, F_FT = 0, 12
"""``frames`` array: the placement of the TCP and of the ft site in that joint's frame, each a
rotation (row-major) and a translation."""
FRAMES_SIZE = F_FT + 12

# -- offsets into MuJoCo's data (adapters.mujoco.data_view) for the mujoco_* functions -----------
M_QPOS, M_QVEL, M_TCP_XPOS, M_TCP_XMAT, M_FT_XPOS, M_FT_XMAT, M_BIAS, M_CTRL, M_FORCE = range(9)
M_VADR, M_MODEL, M_DATA, M_TCP, M_JAC_SITE, M_FULL_M, M_NV = range(9, 16)
"""``index`` array: offsets in the flat view of ``data`` of the robot's first qpos and qvel,
the TCP and ft site positions and rotations, the arm's first bias force, the robot's first
actuator control and the ft_force sensor (ft_torque follows); then the robot's first dof
(a column of ``mj_jacSite``'s Jacobians), the addresses of the ``mjModel`` and ``mjData``, the
TCP site id, the addresses of MuJoCo's ``mj_jacSite`` and ``mj_fullM``, and ``nv``."""
M_SIZE = M_NV + 1
