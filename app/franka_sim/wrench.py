"""The external wrench a Franka reports, estimated from MuJoCo's contact forces on the hand.

franky-sim 1.0.4 sends ``O_F_ext_hat_K`` and ``K_F_ext_hat_K`` as zeros, so a force end
condition never fires against it. Here the wrench is summed from every contact between the
hand's bodies (the hand and its fingers) and anything that is not the robot, at the stiffness
frame K (the TCP unless ``EE_T_K`` moves it). Franka's sign: the wrench the robot exerts on
its environment, so pressing down on a table reads a negative force along z (libfranka issue
#26). ``K_F_ext_hat_K`` is the same wrench in K's axes; ``tau_ext_hat_filtered`` is
``J_Kᵀ · O_F_ext_hat_K``. Unlike the real arm's estimate (from the joint torque sensors,
model-based, filtered, with a bias of a newton or two), this one is exact and unfiltered, and
it sees contacts on the hand only.
"""

from __future__ import annotations

from dataclasses import dataclass

import mujoco
import numpy as np


@dataclass(frozen=True)
class HandContacts:
    """Which bodies of a compiled model are the hand and which the robot."""

    hand: frozenset[int]
    robot: frozenset[int]
    hand_body: int
    dofs: tuple[int, ...]
    """The seven arm joints' degrees of freedom, in joint order."""

    @classmethod
    def of(cls, model: mujoco.MjModel, hand: str, dofs: tuple[int, ...]) -> HandContacts:
        """The subtree of body ``hand`` and the whole tree of the robot it belongs to."""
        hand_id = model.body(hand).id
        root = int(model.body_rootid[hand_id])
        robot = frozenset(b for b in range(model.nbody) if int(model.body_rootid[b]) == root)
        return cls(frozenset(_subtree(model, hand_id)), robot, hand_id, dofs)


def _subtree(model: mujoco.MjModel, top: int) -> set[int]:
    found = {top}
    for body in range(top + 1, model.nbody):  # a body's children come after it
        if int(model.body_parentid[body]) in found:
            found.add(body)
    return found


def environment_wrench(
    contacts: HandContacts, model: mujoco.MjModel, data: mujoco.MjData, point: np.ndarray
) -> np.ndarray:
    """Force and torque (about ``point``, world axes) that the environment exerts on the
    hand through its contacts now."""
    total = np.zeros(6)
    local = np.zeros(6)
    for i in range(data.ncon):
        contact = data.contact[i]
        body1 = int(model.geom_bodyid[contact.geom1])
        body2 = int(model.geom_bodyid[contact.geom2])
        if body1 in contacts.hand and body2 not in contacts.robot:
            sign = -1.0  # the force of the contact acts on geom2; the hand is geom1
        elif body2 in contacts.hand and body1 not in contacts.robot:
            sign = 1.0
        else:
            continue
        mujoco.mj_contactForce(model, data, i, local)
        axes = contact.frame.reshape(3, 3).T  # the frame's rows are its axes
        force = sign * (axes @ local[:3])
        torque = sign * (axes @ local[3:])
        total[:3] += force
        total[3:] += torque + np.cross(contact.pos - point, force)
    return total


def franka_wrenches(
    contacts: HandContacts,
    model: mujoco.MjModel,
    data: mujoco.MjData,
    o_t_k: np.ndarray,
) -> tuple[tuple[float, ...], tuple[float, ...], tuple[float, ...]]:
    """``O_F_ext_hat_K``, ``K_F_ext_hat_K`` and ``tau_ext_hat_filtered`` for the stiffness
    frame pose ``o_t_k`` (4×4, base frame = world frame)."""
    point, rotation = o_t_k[:3, 3], o_t_k[:3, :3]
    on_robot = -environment_wrench(contacts, model, data, point)
    in_k = np.concatenate([rotation.T @ on_robot[:3], rotation.T @ on_robot[3:]])
    jacp, jacr = np.zeros((3, model.nv)), np.zeros((3, model.nv))
    mujoco.mj_jac(model, data, jacp, jacr, point, contacts.hand_body)
    jacobian = np.vstack([jacp, jacr])[:, list(contacts.dofs)]
    tau = jacobian.T @ on_robot
    return tuple(on_robot.tolist()), tuple(in_k.tolist()), tuple(tau.tolist())
