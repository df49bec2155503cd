"""The checks of a run that carries liquid on its bodies (film and bonds modes), inside yade."""
import math


def conserved(ck, law, total0, where):
    """films + bridges + removed of law.liquidTotals() equal total0 to 1e-12 relative, every free volume
    finite and >= 0, every force finite; returns the totals."""
    from yade import O
    t = law.liquidTotals()
    ck.close(t["total"], total0, 1e-12, where + ": free + bridges + removed", "the liquid at the start (conservation)")
    films = [b.state.film for b in O.bodies if b]
    ck.true(min(films) >= 0 and all(math.isfinite(f) for f in films), where + ": every free volume finite and >= 0")
    forces = [O.forces.f(b.id).norm() for b in O.bodies if b]
    ck.true(all(math.isfinite(f) for f in forces), where + ": every force finite")
    return t
