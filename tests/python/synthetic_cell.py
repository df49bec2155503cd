"""A synthetic shear cell for the analysis tests (imported by test_cellanalysis.py and test_cell_studies.py):
particles on a lattice moving with omega/Omega = 1/2 + 1/2 erf((r - Rc)/W) and no contacts, and
snapshots with contacts of known gaps and forces in known coarse cells."""
import json

import numpy as np

from yade_capillary import fits

CFG = dict(R=2.0e-3, Ri=0.01, Ro=0.06, Rs=0.045, H=0.03, period=10.0)
RC, W = 0.04, 0.006


def make_run(d):
    """run.json and two snapshots of the synthetic band in directory d (a pathlib.Path); returns d."""
    Omega = 2 * np.pi / CFG["period"]
    with open(d / "run.json", "w") as f:
        json.dump({"cfg": CFG, "config": "synthetic", "case": "none", "Omega_rad_s": Omega, "torque_rotating_Nm": -1e-4,
                   "torque_static_Nm": 1e-4, "particle_steps_per_s": 0.0}, f)
    rng = np.random.default_rng(7)
    rr, zz = np.meshgrid(np.arange(CFG["Ri"] + 1e-3, CFG["Ro"], 4e-4), np.arange(0.5e-3, CFG["H"] + 4e-3, 4e-4), indexing="ij")
    for s in range(2):
        t = rng.uniform(0, 2 * np.pi, rr.size)
        r, z = rr.ravel(), zz.ravel()
        x = np.stack([r * np.cos(t), r * np.sin(t), z], axis=1)
        om = Omega * fits.erf_profile(r, RC, W)
        v = np.stack([-om * x[:, 1], om * x[:, 0], np.zeros_like(r)], axis=1)
        np.savez(d / ("snap_%03d.npz" % s), x=x, v=v, m=np.full(len(r), 1e-6), xP=np.zeros((0, 3)), xI=np.zeros((0, 3)),
                 F=np.zeros((0, 3)), gap=np.zeros(0), t=float(s))
    return d


def contact_snapshot(path, grid, cells, gaps, forces, t, rng):
    """A snapshot whose contacts have their branch middles at the nodes (4 ic + 1, 4 kc + 1) of the coarse
    cells `cells`, the given gaps [m] and |F| [N], between flowing spheres placed at both ends of each
    branch; plus wall contacts (partner point not a sphere) and wall torques, for the torque balance."""
    mid = np.array([(grid.r[4 * ic + 1], grid.z[4 * kc + 1]) for ic, kc in cells])
    theta = rng.uniform(0, 2 * np.pi, len(mid))
    c = np.stack([mid[:, 0] * np.cos(theta), mid[:, 0] * np.sin(theta), mid[:, 1]], axis=1)
    u = rng.normal(size=(len(mid), 3))
    u = 0.6 * CFG["R"] * u / np.linalg.norm(u, axis=1)[:, None]
    xP, xI = c - u, c + u
    F = np.asarray(forces)[:, None] * u / np.linalg.norm(u, axis=1)[:, None]
    wall_x = np.array([[0.011, 0.0, 0.005], [0.0, 0.03, 0.001], [0.05, 0.0, 0.001]])  # inner wall, bottom inside and outside Rs
    wall_c = wall_x + np.array([[0.0005, 0.0, 0.0], [0.0, 0.0, -0.0005], [0.0, 0.0, -0.0005]])
    wall_F = rng.normal(size=(3, 3)) * 1e-3
    x = np.concatenate([xP, xI, wall_x])
    rz = rng.uniform(0.01, 0.06, (5, 2))
    np.savez(path, x=x, v=np.zeros_like(x), m=np.full(len(x), 1e-6), xP=np.concatenate([xP, wall_x]), xI=np.concatenate([xI, wall_c]),
             F=np.concatenate([F, wall_F]), gap=np.concatenate([gaps, [-1e-6] * 3]), t=t,
             static_rz=rz, static_Tz=rng.normal(size=5) * 1e-4, rotating_rz=rz[::-1], rotating_Tz=rng.normal(size=5) * 1e-4)
