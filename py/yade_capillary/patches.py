"""Every patch that yade-capillary makes to YADE's Python objects, each with what it guards, and
install(), the one function that applies them (import inside yade only).

Importing the package patches nothing. yade_capillary.scene.engines() and interaction_loop() call
install(records) when they build a scene; a script that builds its engine list without them, or runs a
scene loaded with O.load in a process that has not, calls install() itself (PendularCheck warns at its
first step when the guards of the ALWAYS group are missing). A patch stays for the rest of the process;
installing again installs only what is missing.

PATCHES lists them, in two groups (docs/design.md explains each and what a user of YADE's other
materials may no longer rely on):

* ALWAYS: what the plugin's engines need to give right results, with or without PendularLoop's records.
  Each adds a step before or after YADE's method and leaves its arguments, results and errors as they
  were, but for two additions: O.run and O.wait raise an error of PendularCheck that YADE's wait()
  missed, and while O.run() runs in the background with records, erase and clear raise RuntimeError.
* RECORDS: what PendularLoop's records need (PendularLoop.keepRecords). Between steps the loop keeps the
  state of sphere-sphere interactions without film or viscosity in a contiguous array of its own; such an
  interaction holds two placeholders shared by all instead of its own ScGeom and PendularPhys, which are
  made from the record when something reads them and dropped after the next step unless Python still
  holds them. These patches make every Python path that reads or changes those objects call PendularLoop
  first (sync: write the records into the objects; drop: and give the changed objects back to the loop);
  while O.run() runs in the background, those that need every record (all but the attributes of objects
  already held) raise RuntimeError when a loop of the scene has records. install(records=True) ends with
  PendularLoop.readersGuarded(): before it, no PendularLoop keeps records.

The wrappers keep the original's name and docstring (functools.wraps), with a note of what they add.
"""
import collections
import functools
import sys

ALWAYS = "always"
RECORDS = "records"

# group: ALWAYS or RECORDS; guards: what the patch is for; targets(w): the (owner, attribute name) pairs it
# replaces, w being yade.wrapper; apply(w): replaces them.
Patch = collections.namedtuple("Patch", "group guards targets apply")

_installed = set()  # indices in PATCHES


# --- the wrappers ------------------------------------------------------------------------------------

def _note(f, note):
    return (f.__doc__ or "") + "\n(yade-capillary: %s)" % note


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
    call.__doc__ = _note(f, "PendularLoop's records are written into the interactions first")
    return call


def _releasing(f, release):
    @functools.wraps(f)
    def call(self, *args, **kw):
        if not self.running:  # YADE stops a running simulation itself; its loop's arrays then stay with it
            release()
        return f(self, *args, **kw)
    call.__doc__ = _note(f, "PendularLoop's records are given back and its arrays freed first")
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
    call.__doc__ = _note(run, "PendularIntegrator reads its NewtonIntegrator's parameters first")
    return call


# --- what each patch replaces and how ----------------------------------------------------------------

def _names(cls, *names):
    return [(cls, n) for n in names]


def _properties(w):
    return [(cls, n) for cls in (w.GenericSpheresContact, w.ScGeom, w.NormPhys, w.NormShearPhys, w.PendularPhys)
            for n, p in vars(cls).items() if isinstance(p, property)]


def _cxx_guards(w):
    w.PendularCheck.installGuards()  # wraps all six at once, once (pkg/yade: PendularCheck::installGuards)


def _property(owner, name, fget=None, fset=None):
    """Replace the property owner.name by one with these getter/setter factories applied (None: kept)."""
    p = vars(owner)[name]
    setattr(owner, name, property(fget(p.fget) if fget and p.fget else p.fget, fset(p.fset) if fset and p.fset else p.fset,
                                  None, p.__doc__))


def _apply_properties(w):
    for cls, name in _properties(w):
        _property(cls, name, lambda f: _reading(f, w.PendularLoop.sync), lambda f: _writing(f, w.PendularLoop.sync))


def _apply_interaction(w):
    for name in ("geom", "phys", "isActive"):
        _property(w.Interaction, name, (lambda f: _making(f, w.PendularLoop.objectsOf)) if name != "isActive" else None,
                  lambda f: _writing(f, w.PendularLoop.sync))


def _apply_setters(w):
    for cls, name in _names(w.Omega, "engines") + _names(w.Engine, "dead"):
        _property(cls, name, None, lambda f: _writing(f, w.PendularLoop.sync))


def _apply_calls(targets, drop):
    def apply(w):
        for owner, name in targets(w):
            setattr(owner, name, _calling(getattr(owner, name), w.PendularLoop.sync, drop))
    return apply


def _utils_functions(w):
    """The functions of yade._utils written in C++ (Boost.Python), also under the names that bind them in
    yade.utils and __main__: yade's launcher has already run `from yade.utils import *` in __main__, where
    scripts and PyRunner commands run."""
    import yade._utils
    namespaces = [m for m in (sys.modules.get("yade.utils"), sys.modules.get("__main__")) if m is not None]
    out = []
    for name, f in vars(yade._utils).items():
        if type(f).__name__ == "function" and type(f).__module__ == "Boost.Python":
            out.append((yade._utils, name))
            out += [(m, name) for m in namespaces if getattr(m, name, None) is f]
    return out


def _apply_utils(w):
    import yade._utils
    wrapped = {}
    for owner, name in _utils_functions(w):  # each name's first pair is yade._utils' own, still YADE's
        if name not in wrapped:
            wrapped[name] = _calling(vars(yade._utils)[name], w.PendularLoop.sync, True)
        setattr(owner, name, wrapped[name])


def _serializing(w):
    return (_names(w.Serializable, "dict", "__getstate__") + _names(w.Omega, "save", "saveTmp", "sceneToString")
            + _names(w.Law2_ScGeom_PendularPhys_Bridge, "liquidTotals"))


def _replacing(w):
    return _names(w.BodyContainer, "replace")


def _apply_release(w):
    for name in ("reset", "load", "loadTmp"):
        setattr(w.Omega, name, _releasing(getattr(w.Omega, name), w.PendularLoop.release))


NEWTON_PARAMETERS = ("damping", "gravity", "dampGravity", "exactAsphericalRot", "mask")


def _apply_newton(w):
    for name in NEWTON_PARAMETERS:
        _property(w.NewtonIntegrator, name, None, lambda f: _notifying(f, w.PendularIntegrator.newtonChanged))


def _apply_run(w):
    w.Omega.run = _refreshing(w.Omega.run, w.PendularIntegrator)


PATCHES = (
    # ALWAYS, in this order (the Python O.run wraps the C++ one).
    Patch(ALWAYS, "an error of PendularCheck raised in O.run's thread reaches Python as ValueError also when YADE's "
          "wait() returned without it, as it does when the simulation thread stopped before wait() looked",
          lambda w: _names(w.Omega, "run", "wait"), _cxx_guards),
    Patch(ALWAYS, "the liquid of the bridges and films that they remove is accounted for "
          "(Law2_ScGeom_PendularPhys_Bridge.liquidTotals), the records written into the objects first",
          lambda w: _names(w.BodyContainer, "erase", "clear") + _names(w.InteractionContainer, "erase", "clear"), _cxx_guards),
    Patch(ALWAYS, "PendularLoop.release first: YADE keeps the engines of the scene they replace alive, and with them the "
          "loop's arrays (and its records' interactions)", lambda w: _names(w.Omega, "reset", "load", "loadTmp"), _apply_release),
    Patch(ALWAYS, "a change is noted for PendularIntegrator (newtonChanged), which reads its NewtonIntegrator's parameters "
          "through Python only when they may have changed, so that the simulation thread does not take the GIL at every "
          "step (YADE's O.reset and O.load hold the GIL while they wait for the step in progress)",
          lambda w: _names(w.NewtonIntegrator, *NEWTON_PARAMETERS), _apply_newton),
    Patch(ALWAYS, "PendularIntegrator.refresh before the simulation thread starts (the same reason)",
          lambda w: _names(w.Omega, "run"), _apply_run),
    # RECORDS
    Patch(RECORDS, "the attributes of the geometry and physics classes (reading: the records written into the objects "
          "that exist; assigning: and the objects given back to the loop, which reads them at its next step)",
          _properties, _apply_properties),
    Patch(RECORDS, "Interaction.geom and .phys (reading: PendularLoop.objectsOf, the interaction's own objects, made from "
          "its record if needed; assigning: sync and drop), .isActive (assigning: sync and drop)",
          lambda w: _names(w.Interaction, "geom", "phys", "isActive"), _apply_interaction),
    Patch(RECORDS, "O.engines and Engine.dead (assigning: every recorded interaction's objects made and the records "
          "dropped, since another loop may read the objects)", lambda w: _names(w.Omega, "engines") + _names(w.Engine, "dead"),
          _apply_setters),
    Patch(RECORDS, "dict(), pickling, O.save, O.saveTmp, O.sceneToString and liquidTotals read every interaction: every "
          "recorded interaction's objects are made and written first", _serializing, _apply_calls(_serializing, False)),
    Patch(RECORDS, "O.bodies.replace changes every interaction: sync and drop", _replacing, _apply_calls(_replacing, True)),
    Patch(RECORDS, "YADE's utils functions written in C++ (getStress, setContactFriction, createInteraction, "
          "unbalancedForce, ...) may read or change any interaction: sync and drop", _utils_functions, _apply_utils),
)


def install(records=True):
    """Install the patches of the ALWAYS group and, with records, those of the RECORDS group, then let
    PendularLoop keep records (PendularLoop.readersGuarded). What is installed already is left as it is."""
    import yade.wrapper as w

    for i, p in enumerate(PATCHES):
        if i not in _installed and (p.group == ALWAYS or records):
            p.apply(w)
            _installed.add(i)
    if records:
        w.PendularLoop.readersGuarded()


def installed():
    """The groups installed in this process, of ALWAYS and RECORDS."""
    return sorted({PATCHES[i].group for i in _installed})


def targets(group=None):
    """The (owner, attribute name) pairs that the patches of `group` (None: all) replace, as they are
    named before they are installed (yade._utils' functions are listed while they are YADE's)."""
    import yade.wrapper as w

    return [t for p in PATCHES if group in (None, p.group) for t in p.targets(w)]
