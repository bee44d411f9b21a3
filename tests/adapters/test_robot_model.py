"""MuJoCo and Pinocchio read the same robot and agree on kinematics and dynamics; robots and
scenes are found by name."""

import mujoco
import numpy as np
import pinocchio as pin
import pytest

from lightrocks.adapters.robots.common import ARM_DOF, FINGER_TRAVEL, FT_SITE, NV, TCP_SITE
from lightrocks.adapters.robots.robot import Robot
from lightrocks.adapters.scene_registry import UnknownRobot, robot, robots

TOLERANCE = 1e-9


@pytest.fixture(scope="module", params=["lwr", "panda"])
def named(request, installed) -> Robot:
    return installed(request.param)


@pytest.fixture(scope="module")
def models(named: Robot):
    mj_model = mujoco.MjModel.from_xml_string(named.mjcf().decode())
    return mj_model, mujoco.MjData(mj_model), named.model()


def random_states(count: int):
    rng = np.random.default_rng(7)
    for _ in range(count):
        q = np.concatenate((rng.uniform(-2.0, 2.0, ARM_DOF), rng.uniform(0, FINGER_TRAVEL, 2)))
        yield q, rng.normal(size=NV)


def test_same_joints(models, named: Robot):
    mj_model, _, model = models
    assert mj_model.nv == model.nv == NV
    names = [mj_model.joint(i).name for i in range(mj_model.njnt)]
    assert names == list(model.names[1:]) == list(named.joints)
    actuators = [mj_model.actuator(i).name for i in range(mj_model.nu)]
    assert actuators == list(named.joints)


def test_kinematics_and_dynamics_agree(models):
    mj_model, mj_data, model = models
    data = model.createData()
    for q, v in random_states(20):
        mj_data.qpos[:] = q
        mj_data.qvel[:] = v
        mujoco.mj_forward(mj_model, mj_data)
        pin.framesForwardKinematics(model, data, q)
        for name in (TCP_SITE, FT_SITE):
            placement, site = data.oMf[model.getFrameId(name)], mj_model.site(name).id
            assert np.allclose(placement.translation, mj_data.site_xpos[site], atol=TOLERANCE)
            assert np.allclose(
                placement.rotation, mj_data.site_xmat[site].reshape(3, 3), atol=TOLERANCE
            )

        tcp, site = model.getFrameId(TCP_SITE), mj_model.site(TCP_SITE).id
        jac_p, jac_r = np.zeros((3, NV)), np.zeros((3, NV))
        mujoco.mj_jacSite(mj_model, mj_data, jac_p, jac_r, site)
        jacobian = pin.computeFrameJacobian(model, data, q, tcp, pin.LOCAL_WORLD_ALIGNED)
        assert np.allclose(jacobian, np.vstack((jac_p, jac_r)), atol=TOLERANCE)

        mass = np.zeros((NV, NV))
        mujoco.mj_fullM(mj_model, mj_data, mass)
        pin_mass = pin.crba(model, data, q)
        pin_mass = np.triu(pin_mass) + np.triu(pin_mass, 1).T
        assert np.allclose(pin_mass, mass, atol=TOLERANCE)

        bias = pin.rnea(model, data, q, v, np.zeros(NV))
        assert np.allclose(bias, mj_data.qfrc_bias, atol=TOLERANCE)


def test_the_robot_names_what_its_models_hold(models, named: Robot):
    """The finger damping the twin uses is the MJCF's; the hand and fingers are bodies in
    both models, the fingers moved by their own joints, and the finger travel is the one the
    native tick is compiled for."""
    mj_model, _, model = models
    assert list(mj_model.dof_damping[ARM_DOF:]) == [named.finger_damping] * 2
    for body in (named.root, named.hand, *named.fingers):
        assert mj_model.body(body).id > 0
        assert model.existFrame(body, pin.BODY)
    for finger, joint in zip(named.fingers, named.finger_joints, strict=True):
        assert mj_model.body(finger).jntadr[0] == mj_model.joint(joint).id
    assert np.all(mj_model.jnt_range[ARM_DOF:] == [0.0, FINGER_TRAVEL])
    assert mj_model.site(FT_SITE).bodyid[0] == mj_model.body(named.hand).id
    assert np.all(mj_model.site(FT_SITE).pos == 0.0)
    assert np.all(mj_model.site(FT_SITE).quat == [1.0, 0.0, 0.0, 0.0])


def test_scene_registry_rejects_unknown_names():
    from lightrocks.adapters.scene_registry import UnknownScene, scene

    assert scene("empty").mjcf.name == "empty.xml"
    for bad in ("nowhere", "../lwr", "lwr", "", None):
        with pytest.raises(UnknownScene, match="unknown scene"):
            scene(bad)


def test_robot_registry_names_the_known_robots_for_an_unknown_one():
    assert robots()["lwr"].device_type == "LWR"
    for bad in ("nowhere", "LWR", "screwing", "", None):
        with pytest.raises(UnknownRobot, match=r"unknown robot .*; known robots: .*lwr"):
            robot(bad)
    assert issubclass(UnknownRobot, ValueError)
