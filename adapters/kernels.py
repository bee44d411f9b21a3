"""The arithmetic of the 1 kHz tick as native code (numba), one call per phase of a tick.

In Python every NumPy or Pinocchio call costs a fixed ~0.5 µs whatever the size of its
arrays, and the controller, the arm state and the wrist sensing needed about 40 of them per
tick, four times the cost of the physics step itself. Here each phase is one compiled
function over preallocated flat buffers: the controller (``cartesian_torque``,
``joint_torque``), the motor commands (``mujoco_actuate``) and the state and sensing after a
step (``mujoco_sense``, ``pinocchio_sense``; the twin's ``twin_forces``/``twin_integrate``
around Pinocchio's ABA). Each buffer has a fixed layout (the offsets below); the Python objects
that own a buffer expose named views of it, so everything outside the tick reads arrays as
before.

The functions are compiled once and cached (numba's ``cache=True``) in ``__pycache__`` next to
this file, or in the user's cache folder where that is not writable (``NUMBA_CACHE_DIR``
overrides both). The cache is keyed on this file (its time stamp and size) and the CPU, and
written atomically, so processes may share it; everything the compiled code depends on is in
this file. A cold start compiles for ~10 s; later starts load in ~0.2 s (``warm_up``).

``exp3`` and ``log3`` follow Pinocchio's algorithms (same Taylor branches and thresholds),
matrix products sum in index order: results equal NumPy's and Pinocchio's to rounding, not bit
for bit (their BLAS/Eigen kernels sum in other orders).
"""

from __future__ import annotations

import math

import numpy as np
from llvmlite import ir
from numba import carray, farray, njit, types
from numba.extending import intrinsic

from lightrocks.adapters import robot_model

ARM_DOF, NV = 7, 9
FINGER_TRAVEL, GRIPPER_BAND = 0.04, 0.002
"""The robot facts the compiled code uses, repeated here because numba's cache is keyed on this
file alone: a change in robot_model that is not made here too fails at import instead of
running stale cached code."""
if (ARM_DOF, NV, FINGER_TRAVEL, GRIPPER_BAND) != (
    robot_model.ARM_DOF,
    robot_model.NV,
    robot_model.FINGER_TRAVEL,
    robot_model.GRIPPER_BAND,
):
    raise ImportError("adapters/kernels.py must repeat the constants of adapters/robot_model.py")

DT = 0.001
"""Control period [s]."""

_JIT = {"cache": True, "error_model": "numpy"}
"""NumPy's error model: a division by zero gives inf/nan as in NumPy, with no Python check."""

_EPS = float(np.finfo(float).eps)
_PREC2 = _EPS ** (1.0 / 3.0)
_PREC3 = _EPS**0.25
"""Pinocchio's ``TaylorSeriesExpansion<double>::precision<2>()`` and ``<3>()``."""

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
T_BOXES = T_BODY + 12
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


@njit(**_JIT)
def finger_push(grip: float, left: float, right: float, closed: float) -> tuple[float, float]:
    """Signed drive (> 0 opens) of each finger at positions ``left``, ``right``: ``|grip|``
    fading out linearly within GRIPPER_BAND of the target, ``closed`` if ``grip`` > 0 else
    fully open."""
    target = closed if grip > 0 else FINGER_TRAVEL
    size = abs(grip)
    return (
        size * min(max((target - left) / GRIPPER_BAND, -1.0), 1.0),
        size * min(max((target - right) / GRIPPER_BAND, -1.0), 1.0),
    )


@njit(**_JIT)
def mujoco_actuate(mj: np.ndarray, arm: np.ndarray, grip: float, index: np.ndarray) -> None:
    """Before a step: arm torques to the arm motors, each finger motor pushes with the grip
    force; and the ft site's rotation, at which the step computes the wrist sensors, is kept
    (the next ``mj_step1`` moves the site)."""
    ctrl, qpos, s = index[M_CTRL], index[M_QPOS], arm[SENSING:]
    for j in range(ARM_DOF):
        mj[ctrl + j] = arm[TAU + j]
    left, right = finger_push(grip, mj[qpos + ARM_DOF], mj[qpos + ARM_DOF + 1], 0.0)
    mj[ctrl + ARM_DOF], mj[ctrl + ARM_DOF + 1] = left, right
    for i in range(9):
        s[S_SENSOR_ROT + i] = mj[index[M_FT_XMAT] + i]


@njit(**_JIT)
def exp3(v0: float, v1: float, v2: float, out: np.ndarray) -> None:
    """Rotation matrix of the rotation vector (Pinocchio's ``exp3``) into ``out`` (9, row-major:
    flat arrays, since a reshape costs a numba call ~25 ns)."""
    t2 = v0 * v0 + v1 * v1 + v2 * v2 + _EPS * _EPS
    t = math.sqrt(t2)
    st, ct = math.sin(t), math.cos(t)
    if t > _PREC3:
        a_vxvx, a_vx = (1 - ct) / t2, st / t
    else:
        a_vxvx, a_vx, ct = 0.5 - t2 / 24, 1.0 - t2 / 6, 1.0 - t2 / 2
    a0, a1, a2 = a_vxvx * v0, a_vxvx * v1, a_vxvx * v2
    out[0] = a0 * v0 + ct
    out[1] = a0 * v1 - a_vx * v2
    out[2] = a0 * v2 + a_vx * v1
    out[3] = a1 * v0 + a_vx * v2
    out[4] = a1 * v1 + ct
    out[5] = a1 * v2 - a_vx * v0
    out[6] = a2 * v0 - a_vx * v1
    out[7] = a2 * v1 + a_vx * v0
    out[8] = a2 * v2 + ct


@njit(**_JIT)
def _theta_axis(i0: int, val: float, r: np.ndarray, axis: np.ndarray) -> float:
    """Angle and axis of a rotation ``r`` (9, row-major) near π from its column ``i0``
    (Pinocchio's ``compute_theta_axis``); returns the angle, ``axis`` receives the unit axis."""
    i1, i2 = (i0 + 1) % 3, (i0 + 2) % 3
    s = math.sqrt(val + _EPS + _EPS * _EPS)
    if r[3 * i2 + i1] < r[3 * i1 + i2]:
        s = -s
    axis[i0] = s / 2
    axis[i1] = 1.0 / (2 * s) * (r[3 * i1 + i0] + r[3 * i0 + i1])
    axis[i2] = 1.0 / (2 * s) * (r[3 * i2 + i0] + r[3 * i0 + i2])
    w = 1.0 / (2 * s) * (r[3 * i2 + i1] - r[3 * i1 + i2])
    norm = math.sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2])
    axis[0] /= norm
    axis[1] /= norm
    axis[2] /= norm
    return 2 * math.atan2(norm, w)


@njit(**_JIT)
def log3(r_in: np.ndarray, out: np.ndarray, r: np.ndarray) -> None:
    """Rotation vector of a rotation matrix ``r_in`` (9, row-major) into ``out`` (3):
    Pinocchio's ``log3``, including its renormalisation and its branches near 0 and π. ``r``
    (9) is scratch space."""
    n0 = math.sqrt(r_in[0] ** 2 + r_in[3] ** 2 + r_in[6] ** 2)
    n1 = math.sqrt(r_in[1] ** 2 + r_in[4] ** 2 + r_in[7] ** 2)
    for i in range(3):
        r[3 * i] = r_in[3 * i] / n0
        r[3 * i + 1] = r_in[3 * i + 1] / n1
    r[2] = r[3] * r[7] - r[6] * r[4]  # col2 = col0 x col1
    r[5] = r[6] * r[1] - r[0] * r[7]
    r[8] = r[0] * r[4] - r[3] * r[1]
    c0 = r[4] * r[8] - r[7] * r[5]  # col0 = col1 x col2
    c1 = r[7] * r[2] - r[1] * r[8]
    c2 = r[1] * r[5] - r[4] * r[2]
    r[0], r[3], r[6] = c0, c1, c2
    tr = r[0] + r[4] + r[8]
    cos_value = (tr - 1) / 2
    if cos_value < -1 + _PREC2:  # θ near π: the axis from the largest diagonal element
        axis = np.empty(3)
        vals = (2 * r[0] - tr + 1, 2 * r[4] - tr + 1, 2 * r[8] - tr + 1)
        if vals[0] >= vals[1]:
            i0 = 0 if vals[0] >= vals[2] else 2
        else:
            i0 = 1 if vals[1] >= vals[2] else 2
        theta = _theta_axis(i0, vals[i0], r, axis)
        out[0], out[1], out[2] = theta * axis[0], theta * axis[1], theta * axis[2]
        return
    acos_expansion = math.sqrt(2 * (1 - cos_value) + _EPS * _EPS)
    if tr <= 3 - _PREC2:
        theta = math.acos(cos_value) if tr >= -1 + _PREC2 else math.pi - acos_expansion
    else:
        theta = acos_expansion
    a0 = 0.5 * (r[7] - r[5])
    a1 = 0.5 * (r[2] - r[6])
    a2 = 0.5 * (r[3] - r[1])
    if theta >= _PREC2:
        t = theta / math.sin(theta)
    else:
        n2 = a0 * a0 + a1 * a1 + a2 * a2
        t = 1.0 + n2 / 6 + n2 * n2 * 3 / 40
    out[0], out[1], out[2] = t * a0, t * a1, t * a2


@njit(**_JIT)
def cholesky(a: np.ndarray, low: np.ndarray) -> None:
    """The lower Cholesky factor L of a symmetric positive definite matrix ``a`` (its lower
    triangle is read) into ``low``, whose upper triangle is left alone."""
    n = a.shape[0]
    for j in range(n):
        total = a[j, j]
        for m in range(j):
            total -= low[j, m] * low[j, m]
        low[j, j] = math.sqrt(total)
        for i in range(j + 1, n):
            total = a[i, j]
            for m in range(j):
                total -= low[i, m] * low[j, m]
            low[i, j] = total / low[j, j]


@njit(**_JIT)
def spd_inverse(a: np.ndarray, out: np.ndarray) -> None:
    """Inverse of a symmetric positive definite matrix by its Cholesky factor L:
    ``a⁻¹ = L⁻ᵀ L⁻¹`` (numba's ``np.linalg.inv`` needs SciPy's LAPACK)."""
    n = a.shape[0]
    low = np.zeros((n, n))
    cholesky(a, low)
    inv = np.zeros((n, n))  # L⁻¹, lower triangular
    for j in range(n):
        inv[j, j] = 1.0 / low[j, j]
        for i in range(j + 1, n):
            total = 0.0
            for m in range(j, i):
                total += low[i, m] * inv[m, j]
            inv[i, j] = -total / low[i, i]
    for i in range(n):
        for j in range(i, n):
            total = 0.0
            for m in range(j, n):
                total += inv[m, i] * inv[m, j]
            out[i, j] = out[j, i] = total


@njit(**_JIT)
def cholesky_solve(low: np.ndarray, b: np.ndarray) -> None:
    """Solve ``L Lᵀ x = b`` in place of ``b``, with L the lower triangle of ``low``."""
    n = b.shape[0]
    for i in range(n):
        total = b[i]
        for m in range(i):
            total -= low[i, m] * b[m]
        b[i] = total / low[i, i]
    for i in range(n - 1, -1, -1):
        total = b[i]
        for m in range(i + 1, n):
            total -= low[m, i] * b[m]
        b[i] = total / low[i, i]


@njit(**_JIT)
def take_mass(arm: np.ndarray, mass: np.ndarray, first: int, upper: bool) -> None:
    """The arm block (at dof ``first``) of a mass matrix: its inverse and diagonal into the arm
    state; with ``upper``, only the upper triangle of ``mass`` is filled (Pinocchio's crba)."""
    block = np.empty((ARM_DOF, ARM_DOF))
    for i in range(ARM_DOF):
        for j in range(ARM_DOF):
            low, high = (j, i) if upper and i > j else (i, j)
            block[i, j] = mass[first + low, first + high]
        arm[MASS_DIAG + i] = block[i, i]
    spd_inverse(block, arm[MASS_INV : MASS_INV + ARM_DOF * ARM_DOF].reshape(ARM_DOF, ARM_DOF))


@intrinsic
def _c_call(typingctx, function, arguments):
    """Call the C function at address ``function`` with a tuple of integer ``arguments``, all
    passed as pointers but the last, passed as a C int if there are five (MuJoCo's
    ``mj_jacSite(m, d, jacp, jacr, site)`` and ``mj_fullM(m, d, dst)``)."""
    count = len(arguments)
    signature = types.void(function, arguments)

    def codegen(context, builder, sig, args):
        pointer = ir.IntType(8).as_pointer()
        values = [builder.extract_value(args[1], i) for i in range(count)]
        kinds = [pointer] * count
        if count == 5:
            kinds[4] = ir.IntType(32)
        converted = [
            builder.trunc(v, kind) if kind is not pointer else builder.inttoptr(v, pointer)
            for v, kind in zip(values, kinds, strict=True)
        ]
        target = builder.inttoptr(args[0], ir.FunctionType(ir.VoidType(), kinds).as_pointer())
        builder.call(target, converted)
        return context.get_dummy_value()

    return signature, codegen


@intrinsic
def _doubles_at(typingctx, address):
    """A pointer to the float64 values at ``address``, for ``carray``/``farray`` to read another
    library's arrays in place (Pinocchio's data, whose arrays Eigen allocates once)."""
    signature = types.CPointer(types.float64)(address)

    def codegen(context, builder, sig, args):
        return builder.inttoptr(args[0], context.get_value_type(sig.return_type))

    return signature, codegen


@njit(**_JIT)
def cartesian_refresh(
    mass_inv: np.ndarray, jac: np.ndarray, rot: np.ndarray, c: np.ndarray
) -> None:
    """The slow terms of Cartesian impedance from the controlled frame's Jacobian and rotation
    and the inverse arm mass matrix: the damping ``D = 2 ζ sqrt(K Λ_ii)``
    with the diagonal of the operational-space inertia Λ = (J M⁻¹ Jᵀ)⁻¹ in task axes, and the
    dynamically consistent null-space projector ``N = I − Jᵀ J̄ᵀ``, ``J̄ = M⁻¹ Jᵀ Λ``, split into
    a constant posture torque and a matrix acting on the joint state."""
    mj = np.zeros((ARM_DOF, 6))  # M⁻¹ Jᵀ
    for i in range(ARM_DOF):
        for j in range(6):
            total = 0.0
            for m in range(ARM_DOF):
                total += mass_inv[i, m] * jac[j, m]
            mj[i, j] = total
    lam_inv = np.zeros((6, 6))
    for i in range(6):
        for j in range(6):
            total = 0.0
            for m in range(ARM_DOF):
                total += jac[i, m] * mj[m, j]
            lam_inv[i, j] = total
        lam_inv[i, i] += LAMBDA_REGULARISATION
    lam = np.zeros((6, 6))
    spd_inverse(lam_inv, lam)
    for b in range(2):  # the diagonal of diag(R, R)ᵀ Λ diag(R, R)
        for i in range(3):
            total = 0.0
            for m in range(3):
                for n in range(3):
                    total += rot[m, i] * lam[3 * b + m, 3 * b + n] * rot[n, i]
            axis = 3 * b + i
            c[C_D + axis] = 2.0 * c[C_RATIO + axis] * math.sqrt(c[C_K + axis] * max(total, 0.0))
    jbar = np.zeros((ARM_DOF, 6))
    for i in range(ARM_DOF):
        for j in range(6):
            total = 0.0
            for m in range(6):
                total += mj[i, m] * lam[m, j]
            jbar[i, j] = total
    ns = c[C_NS_STATE : C_NS_STATE + ARM_DOF * 2 * NV].reshape(ARM_DOF, 2 * NV)
    for i in range(ARM_DOF):
        posture = 0.0
        for j in range(ARM_DOF):
            total = 0.0
            for m in range(6):
                total += jac[m, i] * jbar[j, m]
            projector = (1.0 if i == j else 0.0) - total
            posture += projector * c[C_POSTURE + j]
            ns[i, j] = -NULLSPACE_STIFFNESS * projector
            ns[i, NV + j] = -NULLSPACE_DAMPING * projector
        c[C_NS_POSTURE + i] = NULLSPACE_STIFFNESS * posture


@njit(**_JIT)
def cartesian_frame(arm: np.ndarray, c: np.ndarray) -> None:
    """Pose, Jacobian and twist of the controlled frame ``tcp * task`` into ``c``, when the task
    frame is not the TCP (else the controller reads the arm state's). Flat row-major indexing
    throughout: a reshape costs a numba call."""
    for i in range(3):
        for j in range(3):
            total = 0.0
            for m in range(3):
                total += arm[ROT + 3 * i + m] * c[C_TASK_R + 3 * m + j]
            c[C_FRAME_ROT + 3 * i + j] = total
        total = 0.0
        for m in range(3):
            total += arm[ROT + 3 * i + m] * c[C_TASK_P + m]
        c[C_FRAME_POS + i] = total + arm[POS + i]
    dx = c[C_FRAME_POS] - arm[POS]
    dy = c[C_FRAME_POS + 1] - arm[POS + 1]
    dz = c[C_FRAME_POS + 2] - arm[POS + 2]
    jac, fjac = JAC, C_FRAME_JAC
    for j in range(ARM_DOF):  # linear rows -= skew(d) @ angular rows
        wx, wy, wz = arm[jac + 21 + j], arm[jac + 28 + j], arm[jac + 35 + j]
        c[fjac + j] = arm[jac + j] - (dy * wz - dz * wy)
        c[fjac + 7 + j] = arm[jac + 7 + j] - (dz * wx - dx * wz)
        c[fjac + 14 + j] = arm[jac + 14 + j] - (dx * wy - dy * wx)
        c[fjac + 21 + j], c[fjac + 28 + j], c[fjac + 35 + j] = wx, wy, wz
    for i in range(6):
        total = 0.0
        for j in range(ARM_DOF):
            total += c[fjac + ARM_DOF * i + j] * arm[STATE + NV + j]
        c[C_FRAME_TWIST + i] = total


@njit(**_JIT)
def cartesian_torque(arm: np.ndarray, c: np.ndarray) -> None:
    """One tick of Cartesian impedance (see adapters.control.CartesianImpedance) into the arm
    state's TAU; advances the set point by DT and refreshes the slow terms every SLOW_EVERY
    ticks."""
    duration, elapsed = c[C_DURATION], c[C_ELAPSED]
    s = 1.0 if duration <= 0 else min(elapsed / duration, 1.0)
    c[C_ELAPSED] = elapsed + DT
    moving = s < 1.0
    c[C_MOVING] = 1.0 if moving else 0.0
    if c[C_OFFSET] == 0.0:  # the controlled frame: the TCP, or computed into c
        f, rot, pos, jac, twist = arm, ROT, POS, JAC, TWIST
    else:
        cartesian_frame(arm, c)
        f, rot, pos = c, C_FRAME_ROT, C_FRAME_POS
        jac, twist = C_FRAME_JAC, C_FRAME_TWIST
    if c[C_TICKS] % SLOW_EVERY == 0:
        mass_inv = arm[MASS_INV : MASS_INV + ARM_DOF * ARM_DOF].reshape(ARM_DOF, ARM_DOF)
        jacobian = f[jac : jac + 6 * ARM_DOF].reshape(6, ARM_DOF)
        cartesian_refresh(mass_inv, jacobian, f[rot : rot + 9].reshape(3, 3), c)
    c[C_TICKS] += 1
    e, sc = C_ERRORS, C_SCRATCH  # errors: rows position, linear and angular velocity
    r_set, turn, error, normed, wrench, world = sc, sc + 9, sc + 18, sc + 27, sc + 36, sc + 42
    if moving:
        for i in range(3):
            c[e + i] = c[C_P0 + i] + s * c[C_DP + i] - f[pos + i]
        for i in range(6):
            c[e + 3 + i] = c[C_TWSET + i] - f[twist + i]
        exp3(s * c[C_DR], s * c[C_DR + 1], s * c[C_DR + 2], c[turn : turn + 9])
        for i in range(3):
            for j in range(3):
                total = 0.0
                for m in range(3):
                    total += c[C_R0 + 3 * i + m] * c[turn + 3 * m + j]
                c[r_set + 3 * i + j] = total
    else:
        for i in range(3):
            c[e + i] = c[C_PGOAL + i] - f[pos + i]
        for i in range(6):
            c[e + 3 + i] = -f[twist + i]
        for i in range(9):
            c[r_set + i] = c[C_RGOAL + i]
    for i in range(3):
        for j in range(3):
            total = 0.0  # row i of the errors in task axes: Rᵀ errors[i]
            for m in range(3):
                total += c[e + 3 * i + m] * f[rot + 3 * m + j]
            c[C_LOCAL + 3 * i + j] = total
            total = 0.0  # Rᵀ R_set
            for m in range(3):
                total += f[rot + 3 * m + i] * c[r_set + 3 * m + j]
            c[error + 3 * i + j] = total
    log3(c[error : error + 9], c[C_EROT : C_EROT + 3], c[normed : normed + 9])
    for i in range(3):  # K e + D ė in task axes, force then torque
        c[wrench + i] = c[C_K + i] * c[C_LOCAL + i] + c[C_D + i] * c[C_LOCAL + 3 + i]
        c[wrench + 3 + i] = c[C_K + 3 + i] * c[C_EROT + i] + c[C_D + 3 + i] * c[C_LOCAL + 6 + i]
    for b in range(2):  # back to world axes, per 3-block
        for i in range(3):
            total = 0.0
            for m in range(3):
                total += c[wrench + 3 * b + m] * f[rot + 3 * i + m]
            c[world + 3 * b + i] = total
    for j in range(ARM_DOF):
        total = 0.0
        for i in range(6):
            total += f[jac + ARM_DOF * i + j] * c[world + i]
        posture = 0.0
        for m in range(2 * NV):
            posture += c[C_NS_STATE + 2 * NV * j + m] * arm[STATE + m]
        arm[TAU + j] = total + arm[BIAS + j] + c[C_NS_POSTURE + j] + posture


@njit(**_JIT)
def joint_torque(arm: np.ndarray, c: np.ndarray) -> None:
    """One tick of joint impedance (see adapters.control.JointImpedance) into the arm state's
    TAU, with the damping ``2 ζ sqrt(K M_ii)`` of the current mass matrix."""
    duration, elapsed = c[J_DURATION], c[J_ELAPSED]
    s = 1.0 if duration <= 0 else min(elapsed / duration, 1.0)
    c[J_ELAPSED] = elapsed + DT
    for j in range(ARM_DOF):
        v_set = c[J_VSET + j] if s < 1.0 else 0.0
        error = c[J_Q0 + j] + s * c[J_DQ + j] - arm[STATE + j]
        damping = 2.0 * c[J_RATIO + j] * math.sqrt(c[J_K + j] * arm[MASS_DIAG + j])
        arm[TAU + j] = c[J_K + j] * error + damping * (v_set - arm[STATE + NV + j]) + arm[BIAS + j]


@njit(**_JIT)
def sense(arm: np.ndarray, s: np.ndarray) -> None:
    """Wrist sensing (adapters.sensing) of the raw reading in ``s``, then the peak force and
    the TCP's turn about its own z since command start (unwrapped)."""
    com, r = S_LOAD_COM, FT_ROT  # the load's lever: ft rotation @ centre of mass
    lx = arm[r] * s[com] + arm[r + 1] * s[com + 1] + arm[r + 2] * s[com + 2]
    ly = arm[r + 3] * s[com] + arm[r + 4] * s[com + 1] + arm[r + 5] * s[com + 2]
    lz = arm[r + 6] * s[com] + arm[r + 7] * s[com + 1] + arm[r + 8] * s[com + 2]
    wx, wy, wz = s[S_WEIGHT], s[S_WEIGHT + 1], s[S_WEIGHT + 2]
    fx = -s[S_RAW] - s[S_OFFSET] - wx
    fy = -s[S_RAW + 1] - s[S_OFFSET + 1] - wy
    fz = -s[S_RAW + 2] - s[S_OFFSET + 2] - wz
    tx = -s[S_RAW + 3] - s[S_OFFSET + 3] - (ly * wz - lz * wy)
    ty = -s[S_RAW + 4] - s[S_OFFSET + 4] - (lz * wx - lx * wz)
    tz = -s[S_RAW + 5] - s[S_OFFSET + 5] - (lx * wy - ly * wx)
    dx, dy, dz = (
        arm[FT_POS] - arm[POS],
        arm[FT_POS + 1] - arm[POS + 1],
        arm[FT_POS + 2] - arm[POS + 2],
    )
    tx += dy * fz - dz * fy
    ty += dz * fx - dx * fz
    tz += dx * fy - dy * fx
    a = s[S_ALPHA]
    new = (fx, fy, fz, tx, ty, tz)
    for i in range(6):
        s[S_VALUES + i] = s[S_VALUES + i] + (new[i] - s[S_VALUES + i]) * a
    vx, vy, vz = s[S_VALUES], s[S_VALUES + 1], s[S_VALUES + 2]
    s[S_PEAK] = max(s[S_PEAK], math.sqrt(vx * vx + vy * vy + vz * vz))
    c0, c1, c2 = arm[ROT], arm[ROT + 3], arm[ROT + 6]
    cos = c0 * s[S_R0] + c1 * s[S_R0 + 3] + c2 * s[S_R0 + 6]  # first column of R₀ᵀ R
    sin = c0 * s[S_R0 + 1] + c1 * s[S_R0 + 4] + c2 * s[S_R0 + 7]
    yaw = math.atan2(sin, cos)
    s[S_TURNED] += (yaw - s[S_YAW] + math.pi) % (2 * math.pi) - math.pi
    s[S_YAW] = yaw


@njit(**_JIT)
def slow_tick(arm: np.ndarray) -> bool:
    """Counts a read of the plant's state; whether it refreshes the mass terms."""
    ticks = arm[TICKS] + 1.0
    arm[TICKS] = ticks
    return ticks % SLOW_EVERY == 1


@njit(**_JIT)
def mujoco_sense(
    mj: np.ndarray,
    scratch: np.ndarray,
    index: np.ndarray,
    arm: np.ndarray,
    wrist: bool,
) -> None:
    """The arm state from MuJoCo's data after a step, with MuJoCo's ``mj_jacSite`` of the TCP
    (into ``scratch``, 6 x nv) and, on a ``slow_tick``, ``mj_fullM`` (into ``scratch`` after the
    Jacobians, nv x nv) for the mass terms; with ``wrist``, the raw wrist reading (see
    ``mujoco_actuate``) and ``sense``. MuJoCo's functions are called at their addresses in
    ``index``: one native call for all, where each call through the Python bindings costs
    ~0.5 µs. Neither can fail for valid ids (no allocation, no MuJoCo error)."""
    qpos, qvel, bias, va = index[M_QPOS], index[M_QVEL], index[M_BIAS], index[M_VADR]
    model, data = index[M_MODEL], index[M_DATA]
    nv = index[M_NV]
    jacobians = scratch[: 6 * nv].reshape(6, nv)
    at = scratch.ctypes.data
    _c_call(index[M_JAC_SITE], (model, data, at, at + 8 * 3 * nv, index[M_TCP]))
    if slow_tick(arm):
        _c_call(index[M_FULL_M], (model, data, at + 8 * 6 * nv))
        take_mass(arm, scratch[6 * nv :].reshape(nv, nv), va, False)
    for j in range(NV):
        arm[STATE + j] = mj[qpos + j]
        arm[STATE + NV + j] = mj[qvel + j]
    for i in range(3):
        arm[POS + i] = mj[index[M_TCP_XPOS] + i]
        arm[FT_POS + i] = mj[index[M_FT_XPOS] + i]
    for i in range(9):
        arm[ROT + i] = mj[index[M_TCP_XMAT] + i]
        arm[FT_ROT + i] = mj[index[M_FT_XMAT] + i]
    for j in range(ARM_DOF):
        arm[BIAS + j] = mj[bias + j]
    for i in range(6):
        total = 0.0
        for j in range(NV):
            total += jacobians[i, va + j] * arm[STATE + NV + j]
        arm[TWIST + i] = total
        for j in range(ARM_DOF):
            arm[JAC + i * ARM_DOF + j] = jacobians[i, va + j]
    if not wrist:
        return
    s, force = arm[SENSING:], index[M_FORCE]  # the wrist sensors (site frame) into world axes
    for b in range(2):
        for i in range(3):
            total = 0.0
            for m in range(3):
                total += mj[force + 3 * b + m] * s[S_SENSOR_ROT + 3 * i + m]
            s[S_RAW + 3 * b + i] = total
    sense(arm, s)


@njit(**_JIT)
def _pinocchio(index: np.ndarray, what: int, size: int) -> np.ndarray:
    """One of Pinocchio's arrays (``index`` offsets P_*) in place, flat, column-major."""
    return carray(_doubles_at(index[what]), size)


@njit(**_JIT)
def _place(
    joint_rot: np.ndarray,
    joint_pos: np.ndarray,
    placements: np.ndarray,
    f: int,
    out: np.ndarray,
    rot: int,
    pos: int,
) -> None:
    """World placement of a frame (its placement in its joint at ``placements[f:]``, as F_TCP)
    on its joint's placement (Pinocchio's: rotation column-major): rotation (row-major) into
    ``out[rot:]``, translation into ``out[pos:]``."""
    for r in range(3):
        total = 0.0
        for m in range(3):
            total += joint_rot[r + 3 * m] * placements[f + 9 + m]
        out[pos + r] = total + joint_pos[r]
        for c in range(3):
            total = 0.0
            for m in range(3):
                total += joint_rot[r + 3 * m] * placements[f + 3 * m + c]
            out[rot + 3 * r + c] = total


@njit(**_JIT)
def _frame_placement(
    index: np.ndarray, frames: np.ndarray, f: int, out: np.ndarray, rot: int, pos: int
) -> None:
    """``_place`` for a frame on the joint at P_JOINT_ROT (``frames[f:]``, or the twin's
    T_HAND)."""
    joint_rot, joint_pos = _pinocchio(index, P_JOINT_ROT, 9), _pinocchio(index, P_JOINT_POS, 3)
    _place(joint_rot, joint_pos, frames, f, out, rot, pos)


@njit(**_JIT)
def pinocchio_sense(arm: np.ndarray, index: np.ndarray, frames: np.ndarray, wrist: bool) -> None:
    """The arm state from Pinocchio's results, read in place (``index``): the TCP and ft
    placements, the TCP's LOCAL_WORLD_ALIGNED Jacobian from the world-frame joint Jacobians
    (the arm joints carry the TCP), the nonlinear effects and on a ``slow_tick`` the mass terms;
    then with ``wrist`` the wrist sensing."""
    if slow_tick(arm):
        take_mass(arm, farray(_doubles_at(index[P_M]), (NV, NV)), 0, True)
    _frame_placement(index, frames, F_TCP, arm, ROT, POS)
    _frame_placement(index, frames, F_FT, arm, FT_ROT, FT_POS)
    nle = _pinocchio(index, P_NLE, NV)
    for j in range(ARM_DOF):
        arm[BIAS + j] = nle[j]
    joints = _pinocchio(index, P_J, 6 * NV)
    px, py, pz = arm[POS], arm[POS + 1], arm[POS + 2]
    for c in range(ARM_DOF):  # the velocity of the TCP point: v + ω × p
        at = 6 * c
        wx, wy, wz = joints[at + 3], joints[at + 4], joints[at + 5]
        arm[JAC + c] = joints[at] + wy * pz - wz * py
        arm[JAC + ARM_DOF + c] = joints[at + 1] + wz * px - wx * pz
        arm[JAC + 2 * ARM_DOF + c] = joints[at + 2] + wx * py - wy * px
        arm[JAC + 3 * ARM_DOF + c] = wx
        arm[JAC + 4 * ARM_DOF + c] = wy
        arm[JAC + 5 * ARM_DOF + c] = wz
    for i in range(6):
        total = 0.0
        for c in range(ARM_DOF):
            total += arm[JAC + i * ARM_DOF + c] * arm[STATE + NV + c]
        arm[TWIST + i] = total
    if wrist:
        sense(arm, arm[SENSING:])


@njit(**_JIT)
def twin_step(
    arm: np.ndarray,
    twin: np.ndarray,
    index: np.ndarray,
    frames: np.ndarray,
    finger_speed: float,
    grasp: float,
    alone: bool,
) -> int:
    """A twin step as far as native code goes: generalized forces ``−damping q̇ + τ``, no
    contact yet, and the static boxes whose reach holds the hand origin flagged. With none and
    the arm ``alone`` (no fixture twin to step), the whole step (``twin_integrate``), and
    returns -1; otherwise returns how many boxes are near, and the caller adds the
    interactions and integrates."""
    for j in range(NV):
        twin[T_GENERALIZED + j] = twin[T_DAMPING + j] * arm[STATE + NV + j]
    for j in range(ARM_DOF):
        twin[T_GENERALIZED + j] += arm[TAU + j]
    for i in range(6):
        twin[T_CONTACT + i] = 0.0
    _frame_placement(index, twin, T_HAND, twin, T_PLACEMENT, T_PLACEMENT + 9)
    x, y, z = twin[T_PLACEMENT + 9], twin[T_PLACEMENT + 10], twin[T_PLACEMENT + 11]
    near = 0
    for b in range(T_BOXES, twin.shape[0], T_BOX):
        inside = twin[b] < x < twin[b + 3] and twin[b + 1] < y < twin[b + 4]
        inside = inside and twin[b + 2] < z < twin[b + 5]
        twin[b + BOX_NEAR] = 1.0 if inside else 0.0
        near += inside
    if near or not alone:
        return near
    twin_integrate(arm, twin, index, frames, finger_speed, grasp, False, False)
    return -1


@njit(**_JIT)
def twin_contacts(
    arm: np.ndarray,
    twin: np.ndarray,
    index: np.ndarray,
    frames: np.ndarray,
    links: np.ndarray,
    bodies: np.ndarray,
) -> int:
    """Penalty contacts of the contact bodies' points against the static boxes flagged near:
    a point inside a box is pushed out through the nearest face (spring-damper) with
    regularised Coulomb friction; the forces go into the generalized forces (through the
    point's Jacobian) and the contact wrench at the ft site. Returns which fingers touch a box
    (bit 0: the first, bit 1: the second)."""
    joints = _pinocchio(index, P_J, 6 * NV)
    _frame_placement(index, frames, F_FT, twin, T_PLACEMENT, T_PLACEMENT + 9)
    ft = twin[T_PLACEMENT + 9 : T_PLACEMENT + 12]
    stiffness, damping = twin[T_STIFFNESS], twin[T_CONTACT_DAMPING]
    friction, slip_full = twin[T_FRICTION], twin[T_SLIP]
    place = twin[T_BODY : T_BODY + 12]
    jac = np.empty((3, NV))
    blocked = 0
    for body in range(links.shape[0] // B_INTS):
        link = links[B_INTS * body : B_INTS * body + B_INTS]
        joint_rot = carray(_doubles_at(link[B_ROT]), 9)
        joint_pos = carray(_doubles_at(link[B_POS]), 3)
        _place(
            joint_rot, joint_pos, bodies, B_HEADER * body + B_PLACEMENT, twin, T_BODY, T_BODY + 9
        )
        support = B_HEADER * body + B_SUPPORT
        for b in range(T_BOXES, twin.shape[0], T_BOX):
            if twin[b + BOX_NEAR] == 0.0:
                continue
            box_rot, centre, half = b + BOX_ROT, b + BOX_CENTRE, b + BOX_HALF
            for point in range(link[B_COUNT]):
                at = link[B_START] + 3 * point
                lx, ly, lz = bodies[at], bodies[at + 1], bodies[at + 2]
                wx = place[0] * lx + place[1] * ly + place[2] * lz + place[9]
                wy = place[3] * lx + place[4] * ly + place[5] * lz + place[10]
                wz = place[6] * lx + place[7] * ly + place[8] * lz + place[11]
                ex, ey, ez = wx - twin[centre], wy - twin[centre + 1], wz - twin[centre + 2]
                inside = (
                    twin[box_rot] * ex + twin[box_rot + 3] * ey + twin[box_rot + 6] * ez,
                    twin[box_rot + 1] * ex + twin[box_rot + 4] * ey + twin[box_rot + 7] * ez,
                    twin[box_rot + 2] * ex + twin[box_rot + 5] * ey + twin[box_rot + 8] * ez,
                )
                depth = (
                    twin[half] - abs(inside[0]),
                    twin[half + 1] - abs(inside[1]),
                    twin[half + 2] - abs(inside[2]),
                )
                if depth[0] <= 0 or depth[1] <= 0 or depth[2] <= 0:
                    continue
                axis = 0
                for i in range(1, 3):
                    if depth[i] < depth[axis]:
                        axis = i
                side = 1.0 if inside[axis] > 0 else (-1.0 if inside[axis] < 0 else 0.0)
                normal = np.empty(3)
                for i in range(3):
                    normal[i] = twin[box_rot + 3 * i + axis] * side
                velocity = np.zeros(3)
                for c in range(NV):  # the point's Jacobian: v + ω × point, moving columns
                    col = 6 * c
                    ox, oy, oz = joints[col + 3], joints[col + 4], joints[col + 5]
                    move = bodies[support + c]
                    jac[0, c] = move * (joints[col] + oy * wz - oz * wy)
                    jac[1, c] = move * (joints[col + 1] + oz * wx - ox * wz)
                    jac[2, c] = move * (joints[col + 2] + ox * wy - oy * wx)
                    for i in range(3):
                        velocity[i] += jac[i, c] * arm[STATE + NV + c]
                normal_speed = normal[0] * velocity[0]
                normal_speed += normal[1] * velocity[1] + normal[2] * velocity[2]
                pressure = max(stiffness * depth[axis] - damping * normal_speed, 0.0)
                slip = np.empty(3)
                for i in range(3):
                    slip[i] = velocity[i] - normal_speed * normal[i]
                slip_speed = math.sqrt(slip[0] ** 2 + slip[1] ** 2 + slip[2] ** 2)
                scale = 0.0
                if slip_speed > 0:
                    scale = -friction * pressure * min(slip_speed / slip_full, 1.0) / slip_speed
                force = np.empty(3)
                for i in range(3):
                    force[i] = pressure * normal[i] + scale * slip[i]
                for c in range(NV):
                    total = 0.0
                    for i in range(3):
                        total += jac[i, c] * force[i]
                    twin[T_GENERALIZED + c] += total
                dx, dy, dz = wx - ft[0], wy - ft[1], wz - ft[2]
                fx, fy, fz = force[0], force[1], force[2]
                twin[T_CONTACT] += fx
                twin[T_CONTACT + 1] += fy
                twin[T_CONTACT + 2] += fz
                twin[T_CONTACT + 3] += dy * fz - dz * fy
                twin[T_CONTACT + 4] += dz * fx - dx * fz
                twin[T_CONTACT + 5] += dx * fy - dy * fx
                if body > 0:
                    blocked |= 1 << (body - 1)
    return blocked


@njit(**_JIT)
def twin_integrate(
    arm: np.ndarray,
    twin: np.ndarray,
    index: np.ndarray,
    frames: np.ndarray,
    finger_speed: float,
    grasp: float,
    left_blocked: bool,
    right_blocked: bool,
) -> None:
    """End of a twin step: the arm's accelerations from ``M a = forces − h`` (the arm block of
    Pinocchio's mass matrix and its nonlinear effects, of the step's start), semi-implicit Euler
    of the arm joints, the first-order fingers (``finger_speed`` = grip force / finger damping;
    a blocked finger does not close), and ``twin_wrist`` (ft pose of the step's start)."""
    mass = _pinocchio(index, P_M, NV * NV)
    nle = _pinocchio(index, P_NLE, NV)
    low = twin[T_LOW:T_ACCELERATION].reshape(ARM_DOF, ARM_DOF)
    for i in range(ARM_DOF):  # the lower triangle, from Pinocchio's upper one
        for j in range(i + 1):
            low[i, j] = mass[j + NV * i]
    cholesky(low, low)
    acceleration = twin[T_ACCELERATION:T_PLACEMENT]
    for j in range(ARM_DOF):
        acceleration[j] = twin[T_GENERALIZED + j] - nle[j]
    cholesky_solve(low, acceleration)
    for j in range(ARM_DOF):
        arm[STATE + NV + j] += DT * acceleration[j]
        arm[STATE + j] += DT * arm[STATE + NV + j]
    left, right = finger_push(finger_speed, arm[STATE + ARM_DOF], arm[STATE + ARM_DOF + 1], grasp)
    if left_blocked and left < 0:
        left = 0.0
    if right_blocked and right < 0:
        right = 0.0
    arm[STATE + NV + ARM_DOF], arm[STATE + NV + ARM_DOF + 1] = left, right
    arm[STATE + ARM_DOF] += DT * left
    arm[STATE + ARM_DOF + 1] += DT * right
    twin_wrist(arm, twin, index, frames)


@njit(**_JIT)
def twin_wrist(arm: np.ndarray, twin: np.ndarray, index: np.ndarray, frames: np.ndarray) -> None:
    """The twin's quasi-static wrist reading into the arm state's sensing: what link7 must
    exert to hold the load against the contacts, at the ft pose in Pinocchio's data."""
    s = arm[SENSING:]
    _frame_placement(index, frames, F_FT, twin, T_PLACEMENT, T_PLACEMENT + 9)
    ft = twin[T_PLACEMENT : T_PLACEMENT + 9]
    com = twin[T_LOAD_COM : T_LOAD_COM + 3]
    lx = ft[0] * com[0] + ft[1] * com[1] + ft[2] * com[2]
    ly = ft[3] * com[0] + ft[4] * com[1] + ft[5] * com[2]
    lz = ft[6] * com[0] + ft[7] * com[1] + ft[8] * com[2]
    wx, wy, wz = twin[T_LOAD], twin[T_LOAD + 1], twin[T_LOAD + 2]
    c = twin[T_CONTACT : T_CONTACT + 6]
    s[S_RAW] = -c[0] - wx
    s[S_RAW + 1] = -c[1] - wy
    s[S_RAW + 2] = -c[2] - wz
    s[S_RAW + 3] = -c[3] - (ly * wz - lz * wy)
    s[S_RAW + 4] = -c[4] - (lz * wx - lx * wz)
    s[S_RAW + 5] = -c[5] - (lx * wy - ly * wx)


def warm_up() -> None:
    """Compile (or load from the cache) every kernel now, on scratch buffers, so that the
    first command does not pay for it inside its control loop."""
    arm, cartesian = np.zeros(ARM_SIZE), np.zeros(CARTESIAN_SIZE)
    cartesian_torque(arm, cartesian)
    joint_torque(arm, np.zeros(JOINT_SIZE))
    mj, index = np.zeros(4 * NV), np.zeros(M_SIZE, dtype=np.int64)
    mujoco_actuate(mj, arm, 1.0, index)
    # stand-ins for Pinocchio's data (P_J … P_JOINT_POS), alive while the functions read them
    stand_ins = (np.zeros(6 * NV), np.zeros(NV), np.eye(NV).reshape(-1), np.eye(3).reshape(-1))
    stand_ins += (np.zeros(3),)
    index = np.array([a.ctypes.data for a in stand_ins], dtype=np.int64)
    frames = np.zeros(FRAMES_SIZE)
    pinocchio_sense(arm, index, frames, True)
    twin = np.zeros(TWIN_SIZE + T_BOX)
    twin_step(arm, twin, index, frames, 0.1, 0.0, True)
    twin_contacts(arm, twin, index, frames, np.zeros(0, dtype=np.int64), np.zeros(0))


def warm_up_mujoco(mj: np.ndarray, scratch: np.ndarray, index: np.ndarray) -> None:
    """Compile (or load) ``mujoco_sense``, which calls MuJoCo: on a plant's real arguments,
    whose arm state it leaves alone (a scratch arm buffer)."""
    mujoco_sense(mj, scratch, index, np.zeros(ARM_SIZE), True)
