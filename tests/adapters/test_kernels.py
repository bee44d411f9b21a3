"""The native tick functions agree with the library functions and NumPy forms they replace."""

import shutil
from importlib import import_module
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest
from numba.core.dispatcher import Dispatcher

from lightrocks.adapters import kernels as k
from lightrocks.adapters.kernels.jit import KERNELS, digest


def _rotation_vectors() -> list[np.ndarray]:
    rng = np.random.default_rng(3)
    axes = rng.normal(size=(12, 3))
    axes /= np.linalg.norm(axes, axis=1)[:, None]
    angles = [0.0, 1e-9, 1e-5, 3e-4, 0.01, 0.5, 1.5, 2.5, 3.0, np.pi - 1e-4, np.pi - 1e-7, np.pi]
    return [angle * axis for angle, axis in zip(angles, axes, strict=True)]


@pytest.mark.parametrize("vector", _rotation_vectors(), ids=lambda v: f"{np.linalg.norm(v):.2g}")
def test_exp3_and_log3_follow_pinocchio(vector: np.ndarray) -> None:
    flat = np.empty(9)
    k.exp3(*vector.tolist(), flat)
    rotation = flat.reshape(3, 3)
    assert np.allclose(rotation, pin.exp3(vector), atol=1e-14, rtol=0)
    mine = np.empty(3)
    k.log3(flat, mine, np.empty(9))
    theirs = pin.log3(rotation)
    if np.linalg.norm(theirs) > np.pi - 1e-6:  # ±axis at π: the same rotation
        assert np.allclose(pin.exp3(mine), pin.exp3(theirs), atol=1e-9)
    else:
        assert np.allclose(mine, theirs, atol=1e-12, rtol=0)


def test_log3_renormalises_a_slightly_skewed_rotation() -> None:
    rotation = pin.exp3(np.array([0.2, -0.4, 0.1])) + 1e-7
    mine = np.empty(3)
    k.log3(rotation.reshape(9), mine, np.empty(9))
    assert np.allclose(mine, pin.log3(rotation), atol=1e-13, rtol=0)


def test_spd_inverse_equals_numpy() -> None:
    rng = np.random.default_rng(7)
    a = rng.normal(size=(7, 7))
    spd = a @ a.T + 0.1 * np.eye(7)
    inverse = np.empty((7, 7))
    k.spd_inverse(spd, inverse)
    assert np.allclose(inverse, np.linalg.inv(spd), rtol=1e-10, atol=1e-12)
    assert np.array_equal(inverse, inverse.T)


def test_cholesky_solve_equals_numpy() -> None:
    rng = np.random.default_rng(8)
    a = rng.normal(size=(7, 7))
    spd, b = a @ a.T + 0.1 * np.eye(7), rng.normal(size=7)
    low = np.zeros((7, 7))
    k.cholesky(spd, low)
    assert np.allclose(np.tril(low) @ np.tril(low).T, spd, rtol=0, atol=1e-12)
    x = b.copy()
    k.cholesky_solve(low, x)
    assert np.allclose(x, np.linalg.solve(spd, b), rtol=1e-10, atol=1e-12)


def test_cartesian_refresh_equals_the_numpy_formulas() -> None:
    """Damping from the diagonal of Λ in task axes, and the null-space projector."""
    rng = np.random.default_rng(9)
    c = np.zeros(k.CARTESIAN_SIZE)
    jac = rng.normal(size=(6, 7))
    rot = pin.exp3(rng.normal(size=3))
    a = rng.normal(size=(7, 7))
    mass_inv = np.linalg.inv(a @ a.T + np.eye(7))
    stiffness, ratio, posture = rng.uniform(10, 100, 6), rng.uniform(0.5, 1, 6), rng.normal(size=7)
    c[k.C_K : k.C_K + 6], c[k.C_RATIO : k.C_RATIO + 6] = stiffness, ratio
    c[k.C_POSTURE : k.C_POSTURE + 7] = posture
    k.cartesian_refresh(mass_inv, jac, rot, c)

    lam = np.linalg.inv(jac @ mass_inv @ jac.T + k.LAMBDA_REGULARISATION * np.eye(6))
    r6 = np.kron(np.eye(2), rot)
    damping = 2 * ratio * np.sqrt(stiffness * np.maximum(np.diag(r6.T @ lam @ r6), 0))
    nullspace = np.eye(7) - jac.T @ (mass_inv @ jac.T @ lam).T
    assert np.allclose(c[k.C_D : k.C_D + 6], damping, rtol=1e-9)
    posture_torque = k.NULLSPACE_STIFFNESS * nullspace @ posture
    assert np.allclose(c[k.C_NS_POSTURE : k.C_NS_POSTURE + 7], posture_torque, atol=1e-9)
    state = c[k.C_NS_STATE : k.C_NS_STATE + 7 * 18].reshape(7, 18)
    assert np.allclose(state[:, :7], -k.NULLSPACE_STIFFNESS * nullspace, atol=1e-9)
    assert np.allclose(state[:, 9:16], -k.NULLSPACE_DAMPING * nullspace, atol=1e-9)
    assert not state[:, 7:9].any() and not state[:, 16:].any()


def _dispatchers() -> list:
    """Every compiled function of the kernel modules."""
    folder = Path(k.__file__).parent
    modules = [import_module(f"lightrocks.adapters.kernels.{p.stem}") for p in folder.glob("*.py")]
    found = {id(f): f for m in modules for f in vars(m).values() if isinstance(f, Dispatcher)}
    return list(found.values())


def test_every_kernel_is_cached_under_the_digest_of_all_kernel_modules() -> None:
    """A kernel compiles in what it calls and reads from other kernel modules: its cache must
    be stale when any of them changes, not only its own file."""
    dispatchers = _dispatchers()
    assert len(dispatchers) >= 20
    for dispatcher in dispatchers:
        assert dispatcher._cache._impl.locator.get_source_stamp() == KERNELS, dispatcher


def test_the_digest_changes_with_any_kernel_module(tmp_path: Path) -> None:
    folder = Path(k.__file__).parent
    for path in folder.glob("*.py"):
        shutil.copy(path, tmp_path / path.name)
    assert digest(tmp_path) == KERNELS
    layout = tmp_path / "layout.py"
    layout.write_text(layout.read_text() + "\n")
    assert digest(tmp_path) != KERNELS
