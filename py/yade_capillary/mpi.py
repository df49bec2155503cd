"""Runs under YADE's MPI module yade.mpy (inside yade, started by mpiexec): subdomains and totals.

yade.mpy computes an interaction between bodies of two subdomains on both ranks; the law counts its
bridge only on the rank of the larger subdomain number (Law2_ScGeom_PendularPhys_Bridge.nBridges),
so liquid_totals() sums the ranks' totals without counting a boundary bridge twice.
"""
import os

from yade import O


def rank_and_size():
    """(rank, number of ranks) of this process under mpiexec (Open MPI's environment), (0, 1) otherwise."""
    return int(os.environ.get("OMPI_COMM_WORLD_RANK", 0)), int(os.environ.get("OMPI_COMM_WORLD_SIZE", 1))


def assign_slabs(ranks, axis=0):
    """Give the dynamic bodies of O subdomains 1..ranks-1 by slabs of equal width along `axis`; other
    bodies (walls, fixed) stay on the master (subdomain 0), as yade.mpy expects. ranks: the number
    of MPI processes (>= 2)."""
    if ranks < 2:
        raise ValueError("assign_slabs: ranks = %r must be >= 2 (a master and at least one worker)" % (ranks,))
    dynamic = [b for b in O.bodies if b is not None and b.dynamic]
    lo = min(b.state.pos[axis] for b in dynamic)
    hi = max(b.state.pos[axis] for b in dynamic)
    workers = ranks - 1
    for b in dynamic:
        b.subdomain = 1 + min(workers - 1, int((b.state.pos[axis] - lo) / (hi - lo) * workers)) if hi > lo else 1


def liquid_totals(law):
    """(nBridges, liquidVolume [m^3], liquidFormed [m^3], liquidReleased [m^3]) of the whole scene:
    the law's totals, summed over the ranks under yade.mpy (a collective call: every rank must make
    it), this scene's otherwise."""
    local = (law.nBridges, law.liquidVolume, law.liquidFormed, law.liquidReleased)
    if rank_and_size()[1] < 2:
        return local
    from yade import mpy

    return tuple(mpy.comm.allreduce(x) for x in local)
