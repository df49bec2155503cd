"""Keeps the interactions' Python objects current while PendularLoop computes from its own records
(import inside yade only).

Between steps PendularLoop keeps the state of sphere-sphere interactions without film or viscosity
in a contiguous array of its own (PendularLoop.keepRecords); such an interaction holds two placeholders
shared by all instead of its own ScGeom and PendularPhys, which are made from the record when something
reads them and dropped after the next step unless Python still holds them. guard() wraps every Python
path that reads or changes those objects so that it calls PendularLoop first:

* Interaction.geom and .phys (reading: PendularLoop.objectsOf, the interaction's own objects, made from
  its record if needed);
* the attributes of the geometry and physics classes (reading: sync of the objects that exist; assigning:
  sync and drop, so that the loop reads the changed objects at its next step), Interaction.geom, .phys and
  .isActive (assigning), Omega.engines and Engine.dead (assigning: the objects are made and the records
  dropped, since another loop may read the objects);
* Serializable.dict and pickling, O.save, O.saveTmp and O.sceneToString, Law2_ScGeom_PendularPhys_Bridge.liquidTotals
  (reading: sync, every recorded interaction's objects made), O.bodies.replace (sync and drop);
* O.reset, O.load and O.loadTmp (PendularLoop.release first: YADE keeps the engines of the scene they replace
  alive, and the loop's arrays and records with them);
* while the simulation runs in another thread, all of these but the attributes of objects already held raise
  RuntimeError (the loop makes and drops the objects between steps);
* NewtonIntegrator's damping, gravity, dampGravity, exactAsphericalRot and mask (assigning: noted for
  PendularIntegrator) and O.run (PendularIntegrator.refresh first), so that the simulation thread does
  not take the GIL at every step;
* YADE's utils functions written in C++ (yade._utils: getStress, setContactFriction, createInteraction, ...;
  sync and drop), also under the names that yade's launcher imported into __main__.

O.bodies.erase/clear and O.interactions.erase/clear are wrapped in C++ (PendularCheck) and sync and
drop there. Only after guard() does PendularLoop keep records (PendularLoop.readersGuarded).
"""
import functools
import sys

_guarded = False


def _reading(fget, sync):
    def get(self):
        sync(False, False)  # the objects that exist; Python holds no other
        return fget(self)
    return get


def _making(fget, objects_of):
    def get(self):
        objects_of(self)
        return fget(self)
    return get


def _writing(fset, sync):
    def put(self, value):
        sync(True)
        fset(self, value)
    return put


def _calling(f, sync, drop):
    @functools.wraps(f)
    def call(*args, **kw):
        sync(drop)
        return f(*args, **kw)
    call.__doc__ = (f.__doc__ or "") + "\n(yade-capillary: PendularLoop's records are written into the interactions first)"
    return call


def _releasing(f, release):
    @functools.wraps(f)
    def call(self, *args, **kw):
        if not self.running:  # YADE stops a running simulation itself; its loop's arrays then stay with it
            release()
        return f(self, *args, **kw)
    call.__doc__ = (f.__doc__ or "") + "\n(yade-capillary: PendularLoop's records are given back and its arrays freed first)"
    return call


def _notifying(fset, changed):
    def put(self, value):
        fset(self, value)
        changed()
    return put


def _refreshing(run, integrator):
    @functools.wraps(run)
    def call(self, *args, **kw):
        if not self.running:  # a running simulation's engines are read by its own thread
            for e in self.engines:
                if isinstance(e, integrator):
                    e.refresh()
        return run(self, *args, **kw)
    call.__doc__ = (run.__doc__ or "") + "\n(yade-capillary: PendularIntegrator reads its NewtonIntegrator's parameters first)"
    return call


def guard():
    """Wrap the Python paths that read or change interactions (once per process), then let
    PendularLoop keep records."""
    global _guarded
    if _guarded:
        return
    import yade._utils
    import yade.wrapper as w

    sync = w.PendularLoop.sync
    for cls in (w.GenericSpheresContact, w.ScGeom, w.NormPhys, w.NormShearPhys, w.PendularPhys):
        for name, p in list(vars(cls).items()):
            if isinstance(p, property):
                setattr(cls, name, property(_reading(p.fget, sync) if p.fget else None, _writing(p.fset, sync) if p.fset else None, None, p.__doc__))
    for name in ("geom", "phys", "isActive"):
        p = vars(w.Interaction)[name]
        fget = _making(p.fget, w.PendularLoop.objectsOf) if name in ("geom", "phys") else p.fget
        setattr(w.Interaction, name, property(fget, _writing(p.fset, sync) if p.fset else None, None, p.__doc__))
    for cls, name in ((w.Omega, "engines"), (w.Engine, "dead")):
        p = vars(cls)[name]
        setattr(cls, name, property(p.fget, _writing(p.fset, sync), None, p.__doc__))
    w.Serializable.dict = _calling(w.Serializable.dict, sync, False)
    w.Serializable.__getstate__ = _calling(w.Serializable.__getstate__, sync, False)  # pickling
    for name in ("save", "saveTmp", "sceneToString"):
        setattr(w.Omega, name, _calling(getattr(w.Omega, name), sync, False))
    w.BodyContainer.replace = _calling(w.BodyContainer.replace, sync, True)
    # YADE keeps the engines of a scene that these replace alive: the loop frees what it holds for it first.
    for name in ("reset", "load", "loadTmp"):
        setattr(w.Omega, name, _releasing(getattr(w.Omega, name), w.PendularLoop.release))
    w.Law2_ScGeom_PendularPhys_Bridge.liquidTotals = _calling(w.Law2_ScGeom_PendularPhys_Bridge.liquidTotals, sync, False)
    # yade's launcher has already run `from yade.utils import *` in __main__, where scripts and PyRunner
    # commands run: their bare names (createInteraction, getStress, ...) are rebound there as well.
    namespaces = [m for m in (sys.modules.get("yade.utils"), sys.modules.get("__main__")) if m is not None]
    for name, f in list(vars(yade._utils).items()):
        if type(f).__name__ == "function" and type(f).__module__ == "Boost.Python":
            g = _calling(f, sync, True)
            setattr(yade._utils, name, g)
            for m in namespaces:
                if getattr(m, name, None) is f:
                    setattr(m, name, g)
    # PendularIntegrator reads its NewtonIntegrator's parameters through Python only when they may have
    # changed, so that the simulation thread does not take the GIL at every step (YADE's O.reset and O.load
    # hold the GIL while they wait for the step in progress: a step waiting for it would never end). A
    # change through these setters is noted (read again at the next step), and O.run reads them before the
    # simulation thread starts.
    for name in ("damping", "gravity", "dampGravity", "exactAsphericalRot", "mask"):
        p = vars(w.NewtonIntegrator)[name]
        setattr(w.NewtonIntegrator, name, property(p.fget, _notifying(p.fset, w.PendularIntegrator.newtonChanged), None, p.__doc__))
    w.Omega.run = _refreshing(w.Omega.run, w.PendularIntegrator)
    _guarded = True
    w.PendularLoop.readersGuarded()
