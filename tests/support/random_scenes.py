"""Random wet scenes as a new user builds them, for the stability campaign (inside yade only).

    draw(index, seed)      the parameters of scene `index` of campaign `seed` (reproducible, a dict)
    run_scene(p, steps)    builds and runs one scene; returns its outcome (a dict, see below)
    campaign(n, steps, seed, log)   runs scenes 0..n-1 and counts the outcomes by class

A scene: 150 spheres (radii uniform in [rmin, ratio rmin], ratio up to 4) with random velocities in a
closed box of walls or facets, a random capillary model, rupture rule (with or without Pitois' dynamic
extension), viscosity (0, water's 1e-3, 5e-2 Pa s), liquid mode (fixed, or films with a random formation
and transfer rule), friction, contact parameters, bridge volume, surface tension, contact angle,
detection factor, loop and gravity, run at O.dt = stable_dt() for `steps` steps with an O.saveTmp /
O.loadTmp at half time, as the user guide recommends. Every scene that runs is checked for:
    explosion      a speed above 20 times the largest speed it could reach from its start: the largest
                   initial speed, or the free-fall speed sqrt(2 g L) across the box of side L;
    nonfinite      a position, velocity or force that is not finite;
    negative_total a liquid total below 0, or nBridges = 0 with liquidVolume != 0;
    conservation   film mode: films + bridges + removed off the initial total by more than 1e-12 of it.
A scene whose set-up is refused with a ValueError naming a parameter (a bridge outside its model's
domain, say) counts as refused; any other exception, or a ValueError that names nothing of the scene,
is a failure of class `error`.
"""
import math
import random

from yade import O

import stress
from yade_capillary import kernels, scene

CLASSES = ("explosion", "nonfinite", "negative_total", "conservation", "error")
ETAS = (0.0, 1e-3, 5e-2)  # inviscid, water, 50 x water [Pa s]
# Words a refusal's message must contain one of: the parameter, as the user wrote it.
PARAMETERS = ("Vb", "V*", "volume", "theta", "gamma", "rupture", "model", "eta", "transfer", "formation", "liquid", "tc", "en", "et",
              "frictionAngle", "extrapolate", "film", "ratio", "radius", "calibrateFrom", "linear", "stable_dt")


def draw(index, seed):
    """The parameters of scene `index` of campaign `seed`: the same dict for the same pair."""
    rng = random.Random("%d:%d" % (seed, index))
    eta = rng.choice(ETAS)
    p = {
        "index": index,
        "model": rng.choice(kernels.MODEL_NAMES),
        "rupture": rng.choice(kernels.RUPTURE_NAMES) + ("+pitois" if eta > 0 and rng.random() < 0.5 else ""),
        "eta": eta,
        "liquid": rng.choice(("fixed", "film")),
        "formation": rng.choice(("contact", "films")),
        "transfer": rng.choice(kernels.TRANSFER_NAMES),
        "friction": rng.choice((0.0, 0.3, 0.6)),
        "rmin": rng.uniform(0.25e-3, 1e-3),
        "ratio": rng.uniform(1.0, 4.0),
        "box": rng.choice(("walls", "facets")),
        "loop": rng.choice(scene.LOOPS),
        "gravity": rng.choice((0.0, 9.81)),
        "tc": rng.uniform(1e-4, 5e-4),
        "en": rng.uniform(0.3, 0.95),
        "et": rng.uniform(0.3, 0.95),
        "vstar": 10 ** rng.uniform(-3, -1),
        "gamma": rng.choice((0.02, 0.0206, 0.072)),
        "theta": math.radians(rng.uniform(0, 40)),
        "extrapolate": rng.random() < 0.5,
        "speed": rng.uniform(0.05, 3.0),
        "film_fraction": 10 ** rng.uniform(-4, -2),  # film volume / sphere volume
        "seed": rng.randrange(1 << 30),
    }
    # A detection factor > 1 only with the fused loop: in YADE's InteractionLoop the law resets every
    # pre-contact pair at each step and the Ip2 builds its physics again (for a film pair with the
    # checks of its largest bridge), about 0.1 ms per pair and step: a scene would take minutes.
    p["detection"] = rng.choice((1.0, 1.3)) if p["loop"] == "fused" else 1.0
    return p


def _law():
    return stress.capillary_law()


def _check(p, g, L, v0, total0):
    """The failure classes of the present state (a list of (class, detail))."""
    out = []
    vmax, finite = 0.0, True
    for b in O.bodies:
        if b is None or not b.dynamic:
            continue
        s = b.state
        values = tuple(s.pos) + tuple(s.vel) + tuple(O.forces.f(b.id)) + tuple(O.forces.t(b.id))
        if not all(math.isfinite(x) for x in values):
            finite = False
        else:
            vmax = max(vmax, s.vel.norm())
    bound = 20 * max(v0, math.sqrt(2 * g * L))
    if not finite:
        out.append(("nonfinite", "a position, velocity or force is not finite"))
    if vmax > bound:
        out.append(("explosion", "speed %.3g m/s above %.3g m/s" % (vmax, bound)))
    law = _law()
    totals = {"nBridges": law.nBridges, "liquidVolume": law.liquidVolume, "liquidFormed": law.liquidFormed,
              "liquidReleased": law.liquidReleased, "liquidRemoved": law.liquidRemoved}
    negative = [k for k, v in totals.items() if v < 0]
    if negative or (law.nBridges == 0 and law.liquidVolume != 0):
        out.append(("negative_total", ", ".join("%s = %r" % kv for kv in totals.items())))
    if p["liquid"] == "film":
        t = law.liquidTotals()["total"]
        if not abs(t - total0) <= 1e-12 * total0:
            out.append(("conservation", "total %r against %r at the start" % (t, total0)))
    return out


def run_scene(p, steps=1000, threads=None):
    """Builds scene p (see draw) and runs it `steps` steps at stable_dt(), saved and reloaded at half
    time. Returns {"status": "ran" | "refused" | "failed", "failures": [(class, detail), ...], "vmax": ..}."""
    try:
        stress.box_packing(150, p["model"], rmin=p["rmin"], ratio=p["ratio"], box=p["box"], vstar=p["vstar"], seed=p["seed"],
                           speed=p["speed"], gravity=(0, 0, -p["gravity"]), porosity=0.85, gamma=p["gamma"], theta=p["theta"],
                           tc=p["tc"], en=p["en"], et=p["et"], friction=p["friction"], rupture=p["rupture"],
                           extrapolate=p["extrapolate"], eta=p["eta"])
        mat = O.materials[0]
        if p["liquid"] == "film":
            mat.liquid = "film"
            mat.formation = p["formation"]
            mat.transfer = p["transfer"]
            for b in O.bodies:
                if b.shape.__class__.__name__ == "Sphere":
                    b.state.film = p["film_fraction"] * 4 / 3 * math.pi * b.shape.radius ** 3
        O.engines = scene.engines(gravity=(0, 0, -p["gravity"]), loop=p["loop"], detection_factor=p["detection"])
        L = max(max(b.state.pos) for b in O.bodies if b.shape.__class__.__name__ == "Sphere")
        O.dt = scene.stable_dt()
    except ValueError as e:
        return _refused(e)
    except Exception as e:  # noqa: BLE001 (any other exception is the finding)
        return {"status": "failed", "failures": [("error", "%s at set-up: %s" % (type(e).__name__, e))]}
    v0 = max(b.state.vel.norm() for b in O.bodies if b.dynamic)
    total0 = _law().liquidTotals()["total"] if p["liquid"] == "film" else 0.0
    failures = []
    try:
        for half in (0, 1):
            O.run(steps // 2, True)
            failures = _check(p, p["gravity"], L, v0, total0)
            if failures:
                break
            if half == 0:
                O.saveTmp("random_scene")
                O.loadTmp("random_scene")
                if p["liquid"] == "film":
                    total0_loaded = _law().liquidTotals()["total"]
                    if not abs(total0_loaded - total0) <= 1e-12 * total0:
                        failures = [("conservation", "total %r after O.loadTmp against %r" % (total0_loaded, total0))]
                        break
    except ValueError as e:
        refusal = _refused(e)
        if refusal["status"] == "refused":
            return refusal
        failures = refusal["failures"]
    except Exception as e:  # noqa: BLE001
        failures = [("error", "%s in the run: %s" % (type(e).__name__, e))]
    return {"status": "failed" if failures else "ran", "failures": failures}


def _refused(e):
    text = str(e)
    if any(word in text for word in PARAMETERS):
        return {"status": "refused", "failures": [], "why": text}
    return {"status": "failed", "failures": [("error", "ValueError naming no parameter: %s" % text)]}


def campaign(n, steps=1000, seed=1, log=print):
    """Runs scenes 0..n-1 of campaign `seed`; returns {"ran", "refused", "failed", class: count, "failures": [...]}."""
    counts = dict({"ran": 0, "refused": 0, "failed": 0}, **{c: 0 for c in CLASSES})
    failures = []
    for i in range(n):
        p = draw(i, seed)
        r = run_scene(p, steps)
        counts[r["status"]] += 1
        for cls in sorted({c for c, _ in r["failures"]}):
            counts[cls] += 1
        if r["failures"]:
            failures.append((p, r["failures"]))
            log("scene %d FAILED %s: %s (%s)" % (i, ", ".join(c for c, _ in r["failures"]), r["failures"][0][1],
                                                ", ".join("%s=%s" % (k, p[k]) for k in ("model", "rupture", "eta", "liquid", "loop", "box", "ratio"))))
    counts["failures"] = failures
    return counts
