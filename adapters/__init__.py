"""LightRocks adapters package.

Headless rendering: MuJoCo picks its OpenGL backend from ``MUJOCO_GL`` when ``mujoco`` is first
imported, and its default (GLFW) needs a display. Unless the caller chose one, use EGL when
``libEGL`` is installed, else OSMesa (software). This must run before any ``import mujoco``,
so importing ``adapters`` first is what makes ``video=`` work.
"""

import ctypes.util
import os

if "MUJOCO_GL" not in os.environ:
    os.environ["MUJOCO_GL"] = "egl" if ctypes.util.find_library("EGL") else "osmesa"
