"""The force path after the controller: delay, passivity observer/controller, saturation.

Passivity observer and controller (Hannaford & Ryu)
--------------------------------------------------
B. Hannaford and J.-H. Ryu, "Time-domain passivity control of haptic interfaces", IEEE Trans.
Robotics and Automation 18(1), 1-10, 2002: a passivity observer (PO) integrates the energy
flowing into a one-port, and a passivity controller (PC) adds the variable damping that removes
an observed energy excess.  Here, in the impedance causality of their section IV:

* Port: the virtual environment as seen by the device, i.e. the actuator port.  Its force is
  ``F_d``, the force the controller commands and the hold applies (the device feels ``-F_d``
  on the actuator mass, eq. 25); its flow is the actuator velocity.  Energy into the port is
  positive (the digital side absorbs it); a passive port never has negative energy.
* Velocity estimate: the raw backward difference of the encoder, ``v[k] = (y[k] - y[k-1])/T``
  (never the controller's filtered velocity: the PO's energy must be exact work).
* PO: ``E[k] = E[k-1] + F[k-1] (y[k] - y[k-1])`` with ``F[k-1]`` the force held over the last
  interval (after delay, PC and saturation) -- the work of the held force on the encoder
  displacement, which is :attr:`~analysis.sampled.results.SimulationResult.energy_observed`.
* PC: with ``F`` the force about to be held, the predicted energy is ``W = E[k] + T F v[k]``;
  when ``W < 0`` and ``v[k] != 0``, ``alpha = -W / (T v[k]^2)`` and ``F <- F + alpha v[k]``
  (Hannaford & Ryu's eq. for ``alpha`` in impedance causality), so the predicted energy is 0.
  The true increment uses ``y[k+1] - y[k]`` instead of ``T v[k]``: ``E`` can still dip below
  zero, by at most one sample's energy.  ``alpha`` is capped at ``passivity_max_damping``
  (0, the default, leaves it unbounded, as in the paper): the PC is itself a sampled damper on the backward
  difference, and a damping far above ``m/T`` of the actuator mass can destabilize a flexible
  device (the HBFD without delay: the unbounded PC ends in a 400 N chatter), at the price of
  letting ``E`` go negative while capped.

Order within sample ``k``: sensors -> controller step -> delay line (the force to hold now)
-> PO update with the previous interval -> PC on the force to hold -> peak clip and I^2 t
fold-back -> hold.  Saturation after the PC can undo part of its damping (as on hardware).
"""

from __future__ import annotations

import math

import numpy as np

from analysis.sampled.scenarios import SimulationOptions

__all__ = ["Actuator"]


class Actuator:
    """Delay line, optional PO/PC (module docstring), peak clip and I^2 t fold-back.

    ``size`` is the number of samples (for the PO/PC records); ``energy[k]`` is the PO's
    energy after sample ``k``'s update and ``alpha[k]`` the PC's damping at sample ``k``.
    """

    def __init__(self, options: SimulationOptions, T: float, delay_samples: int, size: int = 0) -> None:
        self.delay = delay_samples
        self.buffer = [0.0] * delay_samples
        self.peak, self.continuous = options.force_peak, options.force_continuous
        self.thermal = self.continuous < math.inf
        self.alpha = T / options.thermal_time_constant
        self.mean_square = 0.0
        self.T = T
        self.observe = options.passivity_observer or options.passivity_control
        self.control = options.passivity_control
        self.max_damping = options.passivity_max_damping or math.inf  # 0 = no cap
        self.k = 0
        self.E = 0.0
        self.y_prev: float | None = None
        self.f_prev = 0.0
        self.energy = np.zeros(size) if self.observe else None
        self.damping = np.zeros(size) if self.observe else None

    def apply(self, u: float, y: float = 0.0) -> float:
        """The force applied for the controller output ``u`` at encoder reading ``y``."""
        if self.delay:
            self.buffer.append(u)
            u = self.buffer.pop(0)
        if self.observe:
            u = self._passivity(u, y)
        fpk, fcont = self.peak, self.continuous
        if u > fpk:
            u = fpk
        elif u < -fpk:
            u = -fpk
        if self.thermal and self.mean_square > fcont * fcont:
            u = min(max(u, -fcont), fcont)
        self.mean_square += self.alpha * (u * u - self.mean_square)
        if self.observe:
            self.f_prev = u
            self.k += 1
        return u

    def _passivity(self, u: float, y: float) -> float:
        """PO update with the last interval, then the PC on the force ``u`` about to be held."""
        k, T = self.k, self.T
        dy = 0.0 if self.y_prev is None else y - self.y_prev
        self.E += self.f_prev * dy
        self.y_prev = y
        a = 0.0
        if self.control and dy != 0.0:
            v = dy / T
            W = self.E + T * u * v
            if W < 0.0:
                a = min(-W / (T * v * v), self.max_damping)
                u = u + a * v
        if k < self.energy.size:
            self.energy[k] = self.E
            self.damping[k] = a
        return u
