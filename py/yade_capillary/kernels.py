"""The pure capillary bridge models of yade-capillary (SI units, radians).

Works in plain ``python3`` (``PYTHONPATH=build/python``: the build assembles the package there, with the
compiled module ``yade_capillary._kernels``) and inside ``yade``. Example::

    import numpy as np
    from yade_capillary import kernels
    a = np.linspace(0, 2e-4, 200)                                   # surface gap [m]
    F = kernels.force("willett_full", a, R1=2.381e-3, R2=2.381e-3,  # radii [m]
                      volume=13.6e-12, gamma=20.6e-3, theta=0.0)   # [m^3], [N/m], [rad]

``force(model, gap, R1, R2, volume, gamma, theta=0, theta2=None, rupture='willett', ...)``
returns the attractive force [N]; ``bridge(...)`` the per-bridge invariants (effective radius,
rupture distance, F(0), adhesive energy); ``rupture_distance(rule, R1, R2, volume, theta)``;
``models()`` lists every model as a dict (name, reference, monotone, own_rupture, and its validity
``domain``: V* = V/R^3, contact angle, size ratio, walls, with the source of the range);
``rupture_rules()`` lists the rules with references. Outside its model's domain a bridge is refused
unless ``extrapolate=True``. Use ``R2=float('inf')`` for a
sphere-wall bridge. Bad input raises ValueError naming the parameter and its allowed range.

``YoungLaplaceBridge(R1, R2, volume, theta1)`` is the exact solver: ``.rupture_gap`` and
``.solve(gap, gamma)`` (force by the neck and contact-line methods, filling angles, pressure).

Viscous bridge forces (Elskamp 2018 eq. 25-29, 33; PendularMat.eta in YADE):
``viscous_normal_force(law, S, v_n, R1, R2, eta, volume)`` (laws ``VISCOUS_NAMES``),
``viscous_tangential(S, n, v_rel, R1, R2, eta, omega1, omega2)`` and
``dynamic_rupture_distance(static, v_rel, eta, gamma)``.

Where the liquid of a breaking bridge goes (the transfer ratio to solid 1): exactly, the solver's
``YoungLaplaceBridge(...).solve(rupture_gap, gamma)["volume1"] / volume``, tabulated as
``exact_transfer(R1, R2, volume, theta1, theta2)``; Elskamp 2018's parabolic bridge
``parabolic_transfer(R1, R2, volume, S, theta1, theta2)``; Richefeu 2008's ``diameter_transfer(R1, R2)``;
``transfer_ratio(rule, ...)`` by name (``TRANSFER_NAMES``, PendularMat.transfer in YADE).

Liquid carried by the particles (PendularMat.liquid = 'film'; Elskamp 2018 eq. 7-10, 34 after Shi &
McCarthy): ``film_contribution(Ri, Rj, film)``, ``wall_film_contribution(Ri, W)``, ``film_thickness(R, film)``.

Liquid shared over bonds (Richefeu 2008 eq. 13-14, V_b = alpha R^3, R = sqrt(R1 R2), every pair within the
debonding distance of its own bond): ``bond_threshold(rule, R1, R2, gap, theta1, theta2)`` and ``bond_cube(R1, R2)``
per candidate pair, ``share_liquid(thresholds, cubes, liquid)`` -> (alpha, bonded), and
``kept_dry(id1, id2, fraction, seed)`` for the pairs kept dry.
"""
from ._kernels import (YoungLaplaceBridge, bond_cube, bond_threshold, bridge, diameter_transfer, dynamic_rupture_distance, exact_transfer,  # compiled module
                       film_contribution, film_thickness, force, kept_dry, models, parabolic_transfer, transfer_ratio, transfer_rules,
                       wall_film_contribution, rupture_distance, rupture_rules, table_axes, viscous_laws, viscous_normal_force,
                       viscous_tangential, share_liquid, willett_coefficients)

__all__ = ["YoungLaplaceBridge", "bond_cube", "bond_threshold", "kept_dry", "share_liquid", "bridge", "diameter_transfer", "dynamic_rupture_distance", "exact_transfer", "film_contribution",
           "film_thickness", "force", "parabolic_transfer", "transfer_ratio", "transfer_rules", "wall_film_contribution", "models", "rupture_distance", "rupture_rules",
           "table_axes", "viscous_laws", "viscous_normal_force", "viscous_tangential", "willett_coefficients", "MODEL_NAMES",
           "RUPTURE_NAMES", "VISCOUS_NAMES", "TRANSFER_NAMES"]

MODEL_NAMES = [m["name"] for m in models()]
RUPTURE_NAMES = [r[0] for r in rupture_rules()]
VISCOUS_NAMES = [r[0] for r in viscous_laws()]
TRANSFER_NAMES = [r[0] for r in transfer_rules()]
