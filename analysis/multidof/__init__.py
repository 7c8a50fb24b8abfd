"""Multi-DOF devices: one structural model, the exact sampled MIMO loop and the worst wall normal.

Issue 25.  Every result of :mod:`analysis.sampled` is for one axis; here the device has ``m``
Cartesian axes at the handle and the wall is rendered in Cartesian space:

* :class:`StructuralModel` -- ``M q'' + C q' + K q = B_a u``, handle velocity ``J_h q'``, sensed
  positions ``C_s q`` (:mod:`analysis.multidof.model`); :class:`RigidCartesianDevice` (the
  handle's ``M_x``, ``C_x``) and :func:`chain_model` (today's chain
  :class:`~analysis.chain.device.Device`) are special cases, and :func:`structural_model` maps
  each to the general model;
* :func:`closed_loop_matrices` / :func:`wall_radii` -- the exact sampled loop of the impedance
  display against an isotropic wall, a plane wall or a full wall matrix, through the velocity
  filter, the zero-order hold and the delay, hands-off or grasped
  (:mod:`analysis.multidof.loop`);
* :func:`critical_wall_stiffness` and :func:`worst_normal` -- the largest stable stiffness of a
  wall, and the plane-wall normal with the smallest one, certified against a dense check of
  directions (:mod:`analysis.multidof.limits`);
* :func:`workspace_map` -- the isotropic and the worst plane-wall critical stiffness over a grid
  of handle positions of a planar five-bar (:class:`~analysis.transparency.five_bar.FiveBar`,
  the linkage's one home, re-exported here), and the design bound, the minimum over the
  workspace with its position (:mod:`analysis.multidof.workspace`); :func:`five_bar_device`
  linearizes the five-bar at one position and refuses unreachable and singular ones by name;
  the map's crossings come from :func:`frequency_first_crossings`: each point's wall-free loop,
  its frequency response computed once and every wall a projection of it (the Nyquist /
  characteristic-locus condition), certified by four eigenvalue computations a wall on the exact
  loop (:mod:`analysis.multidof.loci`);
* :class:`CableDrive`, :func:`cable_drive_model` -- a linkage with a cable drive per joint (motor
  and link angles, ``2n`` coordinates), and its rigid-cable limit :func:`rigid_drive_device`
  (:mod:`analysis.multidof.cable`); :class:`PhantomLinkage` -- a PHANToM-type 3-DOF serial
  linkage, :data:`PHANTOM_15` its preset from Çavuşoğlu, Feygin & Tendick (2002), sources in
  :data:`PHANTOM_15_SOURCES` (:mod:`analysis.multidof.serial`);
* :func:`device_two_port`, :func:`lth_ratio`, :func:`lth_stiffness_bound` -- the two-port of the
  device with a virtual coupling for ``m`` DOF and the absolute-stability criterion of Li,
  Tavakoli & Huang, which is Llewellyn's for one axis (:mod:`analysis.multidof.twoport_mdof`).

The plant is discretized by :func:`analysis.chain.discretize.discretize_zoh` and cached by value
as :func:`analysis.sampled.loop.discrete_plants` is; stability is
:func:`analysis.sampled.loop.is_stable`; crossings are found by
:func:`analysis.sampled.sweeps.first_crossing`.  Numpy and scipy only.

Example
-------
>>> import numpy as np
>>> from analysis.multidof import RigidCartesianDevice, critical_wall_stiffness
>>> dev = RigidCartesianDevice(mass=np.diag([0.2, 0.4]), damping=np.zeros((2, 2)), sample_time=1e-3)
>>> k = critical_wall_stiffness(dev, damping=1.0, delay_samples=1, normal=None)
"""

from __future__ import annotations

from analysis.multidof.cable import CableDrive, cable_drive_model, rigid_drive_device
from analysis.multidof.limits import (
    DEFAULT_DIRECTIONS,
    PER_DECADE,
    WorstNormal,
    check_directions,
    critical_wall_stiffness,
    first_crossings,
    moving_radius,
    narrow_brackets,
    worst_normal,
)
from analysis.multidof.loci import frequency_first_crossings
from analysis.multidof.loop import (
    closed_loop_matrices,
    discrete_plant,
    loop_parts,
    plant_matrices,
    wall_pencil,
    wall_radii,
    wall_shape,
)
from analysis.multidof.model import (
    SYMMETRY_RTOL,
    DeviceLike,
    RigidCartesianDevice,
    StructuralModel,
    chain_model,
    structural_model,
)
from analysis.multidof.serial import (
    PHANTOM_15,
    PHANTOM_15_SOURCES,
    PhantomLinkage,
    serial_cable_model,
    serial_device,
)
from analysis.multidof.twoport_mdof import (
    LTHBound,
    coupled_two_port,
    default_frequencies,
    device_two_port,
    lth_ratio,
    lth_stiffness_bound,
)
from analysis.multidof.workspace import (
    METHODS,
    SINGULAR_RTOL,
    WorkspaceMap,
    WorkspaceMinimum,
    five_bar_device,
    normal_device,
    workspace_map,
)
from analysis.transparency.five_bar import FiveBar

__all__ = [
    "CableDrive",
    "DEFAULT_DIRECTIONS",
    "DeviceLike",
    "FiveBar",
    "METHODS",
    "LTHBound",
    "PER_DECADE",
    "PHANTOM_15",
    "PHANTOM_15_SOURCES",
    "PhantomLinkage",
    "RigidCartesianDevice",
    "SINGULAR_RTOL",
    "SYMMETRY_RTOL",
    "StructuralModel",
    "WorkspaceMap",
    "WorkspaceMinimum",
    "WorstNormal",
    "cable_drive_model",
    "chain_model",
    "check_directions",
    "closed_loop_matrices",
    "coupled_two_port",
    "critical_wall_stiffness",
    "default_frequencies",
    "device_two_port",
    "discrete_plant",
    "first_crossings",
    "five_bar_device",
    "frequency_first_crossings",
    "loop_parts",
    "lth_ratio",
    "lth_stiffness_bound",
    "moving_radius",
    "narrow_brackets",
    "normal_device",
    "plant_matrices",
    "rigid_drive_device",
    "serial_cable_model",
    "serial_device",
    "structural_model",
    "wall_pencil",
    "wall_radii",
    "wall_shape",
    "workspace_map",
    "worst_normal",
]
