"""The class reference of the plugin (docs/reference.md) as Markdown, built from the docstrings of the
classes that the loaded plugin registers in YADE (inside yade only).

    markdown()          the page (tools/make_reference.py writes it, tests/yade/test_reference.py compares)
    plugin_classes()    the names of the classes the plugin library registers, sorted

Everything comes from the running build: the class list from the plugin library's symbols (see
plugin_classes), the attributes from the docstrings YADE's YADE_CLASS_BASE_DOC_ATTRS* macros generate
(text, then :ydefault:, :yattrtype: and :yattrflags:), the defaults from a newly constructed instance.
"""
import ctypes
import inspect
import math
import os
import re

PLUGIN_LIBRARY = "libyadecapillary.so"
REGENERATE = "build/yade-capillary -n -x tools/make_reference.py"
# YADE's own reference, for the YADE classes a docstring or a base names.
YADE_WRAPPER_DOC = "https://yade-dem.org/doc/yade.wrapper.html#yade.wrapper."
# Bits of yade::Attr::flags (lib/serialization/Serializable.hpp), in the order of the enum.
ATTR_FLAGS = (("noSave", 1), ("readonly", 2), ("triggerPostLoad", 4), ("hidden", 8), ("noResize", 16))
FLAG_MEANINGS = (("readonly", "not settable from Python"), ("noSave", "not saved by O.save"),
                 ("triggerPostLoad", "an assignment from Python runs the class's postLoad, which checks the value and updates what depends on it"),
                 ("noResize", "fixed size"))

_TAIL = re.compile(r"\s*:ydefault:`(?P<default>.*?)`\s*:yattrtype:`(?P<type>.*?)`\s*:yattrflags:`(?P<flags>\d+)`\s*$", re.S)
# A unit is a bracketed group without a comma ([s], [N s/m], [-]); [0, 1e9] and the like are ranges.
_UNIT = re.compile(r"\[([^\[\],]+)\]")
_YREF = re.compile(r":yref:`([^`<]*?)(?:\s*<([^`>]*)>)?`")
_ROLE = re.compile(r":[a-z]+:`([^`]*)`")


def _guid_symbol(name):
    """Itanium-mangled boost::archive::detail::extra_detail::init_guid<yade::name>::g."""
    return "_ZN5boost7archive6detail12extra_detail9init_guidIN4yade%d%sEE1gE" % (len(name), name)


class _DlInfo(ctypes.Structure):
    _fields_ = [("dli_fname", ctypes.c_char_p), ("dli_fbase", ctypes.c_void_p), ("dli_sname", ctypes.c_char_p), ("dli_saddr", ctypes.c_void_p)]


def _plugin_path():
    """The plugin library's file as mapped in this process (the real path, not the overlay's link)."""
    with open("/proc/self/maps") as f:
        for line in f:
            fields = line.split(None, 5)
            if len(fields) == 6 and os.path.basename(fields[5].strip()) == PLUGIN_LIBRARY:
                return fields[5].strip()
    raise RuntimeError("%s is not loaded: run this inside build/yade-capillary" % PLUGIN_LIBRARY)


def plugin_classes():
    """Names of the classes that the plugin library registers, sorted.

    YADE_PLUGIN((A)(B)...) in a .cpp defines, for each class it names, the Boost.Serialization export
    object init_guid<yade::A>::g in the library built from that .cpp, and nowhere else (unlike type
    information or inline members, which are copied into every library that uses a class). A class that
    YADE has registered is the plugin's when the plugin library defines that object: looked up through
    the already loaded library, and dladdr must place it in that library's file (a lookup through a
    handle also searches the libraries it depends on). So the list follows the build, with no list kept
    by hand and no headers needed."""
    from yade import system

    path = _plugin_path()
    lib = ctypes.CDLL(path, mode=os.RTLD_NOLOAD | os.RTLD_LAZY)
    dladdr = ctypes.CDLL(None).dladdr
    dladdr.argtypes = [ctypes.c_void_p, ctypes.POINTER(_DlInfo)]
    names = []
    for name in sorted(system.childClasses("Serializable")):
        try:
            address = ctypes.addressof(ctypes.c_char.in_dll(lib, _guid_symbol(name)))
        except ValueError:  # not defined in the library or its dependencies
            continue
        info = _DlInfo()
        if dladdr(address, ctypes.byref(info)) and os.path.realpath(info.dli_fname.decode()) == os.path.realpath(path):
            names.append(name)
    return names


def _format_value(value):
    """A default as a Python literal, the same in every run: floats by repr (shortest round trip), inf and
    nan as such, minieigen vectors by their components; None for anything else (the caller then shows
    the C++ default of the docstring)."""
    if isinstance(value, bool) or value is None:
        return repr(value)
    if isinstance(value, float):
        if math.isnan(value):
            return "nan"
        if math.isinf(value):
            return "inf" if value > 0 else "-inf"
        return repr(value)
    if isinstance(value, (int, str)):
        return repr(value)
    if isinstance(value, (list, tuple)):
        items = [_format_value(v) for v in value]
        if None in items:
            return None
        return ("[%s]" if isinstance(value, list) else "(%s)") % ", ".join(items)
    kind = type(value).__name__
    if re.match(r"Vector\d", kind):  # minieigen: components are floats, or ints for Vector2i, Vector3i
        parts = [_format_value(v) for v in value]
        return None if None in parts else "%s(%s)" % (kind, ", ".join(parts))
    return None


def _anchor(name):
    """The anchor GitHub gives a heading `## name` (a class name: letters, digits and underscores)."""
    return name.lower()


class _Renderer:
    """Turns YADE's Sphinx markup into Markdown, linking the documented classes within the page."""

    def __init__(self, classes):
        self.classes = set(classes)

    def link(self, target, shown=None):
        cls = target.split(".")[0]
        shown = shown or target
        if cls in self.classes:
            return "[`%s`](#%s)" % (shown, _anchor(cls))
        return "[`%s`](%s%s)" % (shown, YADE_WRAPPER_DOC, target)

    def text(self, doc):
        """Markdown of a docstring; outside code spans, no < that Markdown could take for an HTML tag."""
        doc = _YREF.sub(lambda m: self.link(m.group(2) or m.group(1), m.group(1).strip() if m.group(2) else None), doc)
        doc = _ROLE.sub(r"`\1`", doc.replace("``", "`"))
        parts = re.split(r"(`[^`]*`)", doc)
        parts[::2] = [re.sub(r"<(?=[A-Za-z/!?])", r"\\<", p) for p in parts[::2]]
        return "".join(parts).strip()

    def cell(self, doc):
        """Text for a table cell: one line, | escaped (also in code spans, as GitHub's tables require)."""
        return " ".join(self.text(doc).split()).replace("|", "\\|")


def _code(s):
    """s as a Markdown code span (longer fences if s holds backticks)."""
    fence = "`"
    while fence in s:
        fence += "`"
    pad = " " if s.startswith("`") or s.endswith("`") else ""
    return fence + pad + s + pad + fence


def _attributes(cls, instance):
    """Own attributes declared with YADE's attribute macros: name -> dict; other own properties apart."""
    attrs, props = {}, {}
    for name, member in cls.__dict__.items():
        if name.startswith("_") or not isinstance(member, property):
            continue
        doc = member.__doc__ or ""
        m = _TAIL.search(doc)
        if m is None:
            props[name] = {"doc": doc.strip(), "writable": member.fset is not None}
            continue
        text = doc[:m.start()].strip()
        unit = _UNIT.search(text)
        flags = int(m.group("flags"))
        names = [n for n, bit in ATTR_FLAGS if flags & bit]
        rest = flags & ~sum(bit for _, bit in ATTR_FLAGS)
        if rest:
            names.append("0x%x" % rest)
        value = _format_value(getattr(instance, name)) if instance is not None else None
        attrs[name] = {"text": text, "type": m.group("type").strip(), "unit": unit.group(1).strip() if unit else "",
                       "flags": names, "default": value if value is not None else m.group("default").strip()}
    return attrs, props


def _methods(cls):
    """Own public methods: name -> (static, [(signature, text), ...]) from Boost.Python's docstrings,
    which give each overload as an unindented signature line followed by its indented text."""
    out = {}
    for name, member in cls.__dict__.items():
        if name.startswith("_"):
            continue
        static = isinstance(member, staticmethod)
        func = member.__func__ if static else member
        if isinstance(member, property) or not callable(func):
            continue
        overloads = []
        for line in (func.__doc__ or "").strip("\n").splitlines():
            if line.startswith(name + "("):
                sig = " ".join(line.split())
                overloads.append([sig[:-2].rstrip() if sig.endswith(" :") else sig, []])
            elif overloads:  # text, also a note that a Python wrapper appended unindented
                overloads[-1][1].append(line.strip())
        out[name] = (static, [(sig, " ".join(w for w in text if w)) for sig, text in overloads])
    return out


def _sorted(names):
    return sorted(names, key=lambda n: (n.lower(), n))


def _class_section(name, r):
    import yade.wrapper

    cls = getattr(yade.wrapper, name)
    try:
        instance = cls()
    except Exception:  # no default constructor: the docstring's C++ defaults are shown instead
        instance = None
    base = cls.__bases__[0].__name__
    lines = ["## %s" % name, "", "Base: %s" % r.link(base), "", r.text(cls.__doc__ or ""), ""]
    attrs, props = _attributes(cls, instance)
    if attrs:
        lines += ["| attribute | type | default | unit | flags | description |", "|---|---|---|---|---|---|"]
        for a in _sorted(attrs):
            d = attrs[a]
            lines.append("| %s | %s | %s | %s | %s | %s |" % (
                _code(a), _code(d["type"]), _code(d["default"]) if d["default"] else "", r.cell(d["unit"]) if d["unit"] else "",
                ", ".join(d["flags"]), r.cell(d["text"])))
        lines.append("")
    else:
        lines += ["No attributes of its own.", ""]
    if props:
        lines += ["Properties (computed, not attributes: not saved):", "", "| property | access | description |", "|---|---|---|"]
        for p in _sorted(props):
            lines.append("| %s | %s | %s |" % (_code(p), "read-write" if props[p]["writable"] else "read-only", r.cell(props[p]["doc"])))
        lines.append("")
    methods = _methods(cls)
    if methods:
        lines += ["Methods:", ""]
        for m in _sorted(methods):
            static, overloads = methods[m]
            for sig, text in overloads:
                lines.append("- %s%s: %s" % (_code(sig), " (static)" if static else "", r.text(text)))
        lines.append("")
    return lines


def _scene_section():
    """Public functions of yade_capillary.scene, each with the first paragraph of its docstring."""
    from yade_capillary import scene

    lines = ["## Python helpers: yade_capillary.scene", "",
             "The public functions of the Python package's module that sets up scenes for these classes (engine lists, "
             "time step), each with the first paragraph of its docstring (`help(yade_capillary.scene.<name>)` gives the rest).", ""]
    funcs = [(n, f) for n, f in inspect.getmembers(scene, inspect.isfunction) if not n.startswith("_") and f.__module__ == scene.__name__]
    for n, f in sorted(funcs):
        summary = " ".join((inspect.getdoc(f) or "").split("\n\n")[0].split())
        lines.append("- %s: %s" % (_code(n + str(inspect.signature(f))), summary))
    lines.append("")
    return lines


def markdown(classes=None):
    """The page docs/reference.md: every class of `classes` (default: plugin_classes()), then the
    helpers of yade_capillary.scene. Ends with exactly one newline."""
    # yade_capillary.patches wraps some of the plugin's methods and notes it in their docstrings: the page
    # shows them so, whether or not the caller installed the patches already.
    from yade_capillary import patches

    patches.install()

    classes = _sorted(classes if classes is not None else plugin_classes())
    r = _Renderer(classes)
    lines = ["# Class reference", "",
             "The classes that the yade-capillary plugin (%s) registers in YADE, generated from the docstrings of the "
             "build by `tools/reference.py`; do not edit by hand. Regenerate it with" % PLUGIN_LIBRARY, "",
             "    " + REGENERATE, "",
             "(`tests/yade/test_reference.py` fails when this page differs from what the build generates).", "",
             "Each class lists its own attributes, not those inherited from its base (see YADE's reference for those). "
             "The default is the value of a newly constructed object; the unit is the bracketed unit of the description "
             "([-]: dimensionless; blank where the description gives none). Flags are YADE's attribute flags: "
             + "; ".join("%s: %s" % f for f in FLAG_MEANINGS)
             + ". Attributes flagged hidden are internal and not exposed to Python, so they are not listed.", "",
             "Classes: " + ", ".join("[%s](#%s)" % (c, _anchor(c)) for c in classes) + ".", ""]
    for name in classes:
        lines += _class_section(name, r)
    lines += _scene_section()
    return "\n".join(lines).rstrip("\n") + "\n"
