# Shear-cell run options that validation runs rely on: giving a dry prepared cell a liquid
# (every contact of the packing gets a bridge of the case's volume at the first step, and the
# liquid totals account for it) and running it with another configuration's run parameters only
# (configurations added to shearcell.CONFIGS, as the studies add theirs, scripts/studies/cell_configs.py).
from yade import O
from yade.utils import sphere

from yade_capillary import shearcell
from yade_capillary.scene import engines
from testing import Checker

ck = Checker("test_shear_cell_setup")
cfg = shearcell.CONFIGS["ci"]
R = cfg["R"]

# Three spheres in a row, each pair overlapping by 1 % of R: two dry contacts.
O.reset()
mat = O.materials.append(shearcell._material(cfg, "dry"))
for k in range(3):
    O.bodies.append(sphere((k * 1.99 * R, 0, 0), R, material=mat))
O.engines = engines()
O.dt = 0.01 * cfg["tc"]
O.step()
real = [I for I in O.interactions if I.isReal]
ck.true(len(real) == 2 and not any(I.phys.wet for I in real), "dry packing: 2 dry contacts (%d)" % len(real))

info = {"case": "dry", "config": "ci", "cfg": dict(cfg)}
shearcell._set_case(info, "wet74.2nl")
wet = shearcell.CASES["wet74.2nl"]
ck.true(info["case"] == "wet74.2nl" and O.materials[0].wet and O.materials[0].model == wet["model"], "material and info take the case")
O.engines = engines()  # as run() does: a new collider finds the overlaps again
O.step()
real = [I for I in O.interactions if I.isReal]
ck.true(len(real) == 2 and all(I.phys.wet and I.phys.active for I in real), "both contacts have a bridge after the first step")
for I in real:
    ck.close(I.phys.Vb, wet["Vb"], 1e-12, "bridge volume", "CASES['wet74.2nl']")
ck.close(capillaryLaw.liquidFormed, 2 * wet["Vb"], 1e-12, "liquid formed = 2 bridges", "CASES['wet74.2nl']")
ck.close(capillaryLaw.liquidVolume, 2 * wet["Vb"], 1e-12, "liquid in bridges = 2 bridges", "CASES['wet74.2nl']")
ck.raises(ValueError, lambda: shearcell._set_case(info, "wet13.6nl"), ["case", "dry"], "a wet cell cannot take another liquid")
ck.raises(ValueError, lambda: shearcell._set_case(dict(info, case="dry"), "humid"), ["case", "humid", "wet74.2nl"], "unknown case")

# Run parameters only: a cell prepared as `validation` runs as `validation_2s`, not as `ci`.
shearcell.CONFIGS["validation_2s"] = dict(shearcell.VALIDATION, run_s=2.0, snapshots=10, snapshot_dt_s=0.1)
shearcell.CONFIGS["validation_5s"] = dict(shearcell.VALIDATION, run_s=3.0, snapshots=12)
shearcell.CONFIGS["validation_g22"] = dict(shearcell.VALIDATION, g=2.2 * shearcell.GRAVITY)
prepared = {"case": "dry", "config": "validation", "cfg": dict(shearcell.CONFIGS["validation"])}
shearcell._set_config(prepared, "validation_2s")
ck.true(prepared["cfg"]["run_s"] == shearcell.CONFIGS["validation_2s"]["run_s"] and prepared["config"] == "validation_2s",
        "validation_2s run parameters taken")
ck.raises(ValueError, lambda: shearcell._set_config(prepared, "ci"), ["config", "Ro", "period"], "another cell is refused")
ck.raises(ValueError, lambda: shearcell._set_config(prepared, "huge"), ["config", "huge"], "unknown configuration")

# Another gravity is another cell: validation_g22 is prepared on its own and runs under its g.
ck.true(shearcell.preparation_of("validation_5s") == "validation" and shearcell.preparation_of("validation_g22") == "validation_g22",
        "validation_5s shares the validation packing, validation_g22 does not")
ck.raises(ValueError, lambda: shearcell._set_config(prepared, "validation_g22"), ["config", "in g"], "a cell prepared under 1 g refuses 2.2 g")
ck.raises(ValueError, lambda: shearcell.preparation_of("validation_g3"), ["config", "validation_g3"], "unknown configuration")
g22 = {"case": "dry", "config": "validation_g22", "cfg": dict(shearcell.CONFIGS["validation_g22"]), "rotating": [0]}
newton = [e for e in shearcell.run_engines(g22) if type(e).__name__ == "NewtonIntegrator"]
ck.close(newton[0].gravity[2], -2.2 * 9.81, 1e-12, "NewtonIntegrator's gravity under validation_g22", "validation_g22: 2.2 g")
newton = [e for e in shearcell.run_engines(dict(prepared, rotating=[0])) if type(e).__name__ == "NewtonIntegrator"]
ck.close(newton[0].gravity[2], -9.81, 1e-12, "NewtonIntegrator's gravity of the validation cell", "shearcell.GRAVITY")
ck.finish()
