"""MuJoCo and Pinocchio read the same robot file and agree on kinematics and dynamics."""

import mujoco
import numpy as np
import pinocchio as pin
import pytest

from lightrocks.adapters.robot_model import (
    ARM_DOF,
    FINGER_TRAVEL,
    NV,
    ROBOT_FILE,
    TCP_SITE,
    load_robot,
)

TOLERANCE = 1e-9


@pytest.fixture(scope="module")
def models():
    mj_model = mujoco.MjModel.from_xml_path(str(ROBOT_FILE))
    return mj_model, mujoco.MjData(mj_model), load_robot()


def random_states(count: int):
    rng = np.random.default_rng(7)
    for _ in range(count):
        q = np.concatenate((rng.uniform(-2.0, 2.0, ARM_DOF), rng.uniform(0, FINGER_TRAVEL, 2)))
        yield q, rng.normal(size=NV)


def test_same_joints(models):
    mj_model, _, robot = models
    assert mj_model.nv == robot.nv == NV
    names = [mj_model.joint(i).name for i in range(mj_model.njnt)]
    assert names == list(robot.names[1:])


def test_kinematics_and_dynamics_agree(models):
    mj_model, mj_data, robot = models
    data = robot.createData()
    tcp = robot.getFrameId(TCP_SITE)
    site = mj_model.site(TCP_SITE).id
    for q, v in random_states(20):
        mj_data.qpos[:] = q
        mj_data.qvel[:] = v
        mujoco.mj_forward(mj_model, mj_data)
        pin.framesForwardKinematics(robot, data, q)
        placement = data.oMf[tcp]
        assert np.allclose(placement.translation, mj_data.site_xpos[site], atol=TOLERANCE)
        assert np.allclose(
            placement.rotation, mj_data.site_xmat[site].reshape(3, 3), atol=TOLERANCE
        )

        jac_p, jac_r = np.zeros((3, NV)), np.zeros((3, NV))
        mujoco.mj_jacSite(mj_model, mj_data, jac_p, jac_r, site)
        jacobian = pin.computeFrameJacobian(robot, data, q, tcp, pin.LOCAL_WORLD_ALIGNED)
        assert np.allclose(jacobian, np.vstack((jac_p, jac_r)), atol=TOLERANCE)

        mass = np.zeros((NV, NV))
        mujoco.mj_fullM(mj_model, mj_data, mass)
        pin_mass = pin.crba(robot, data, q)
        pin_mass = np.triu(pin_mass) + np.triu(pin_mass, 1).T
        assert np.allclose(pin_mass, mass, atol=TOLERANCE)

        bias = pin.rnea(robot, data, q, v, np.zeros(NV))
        assert np.allclose(bias, mj_data.qfrc_bias, atol=TOLERANCE)


def test_scene_registry_rejects_unknown_names():
    from lightrocks.adapters.scene_registry import UnknownScene, scene

    assert scene("empty").mjcf.name == "empty.xml"
    for bad in ("nowhere", "../lwr", "lwr", "", None):
        with pytest.raises(UnknownScene, match="unknown scene"):
            scene(bad)


def test_finger_damping_constant_matches_the_model(models):
    from lightrocks.adapters.robot_model import FINGER_DAMPING

    mj_model, _, _ = models
    assert list(mj_model.dof_damping[ARM_DOF:]) == [FINGER_DAMPING, FINGER_DAMPING]
