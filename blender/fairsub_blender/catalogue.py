"""The scheme menu and the options of each scheme, read from the fairsub package's catalogue
(``fairsub.schemes()``, ``fairsub.scheme_options(name)``) when the add-on registers, so a scheme
or an option added to fairsub appears here without a change to the add-on.

Options are Blender properties named ``opt_<name>`` (``opt_split_ratio``): an enum for an
option with a fixed set of values (its first item, ``DEFAULT``, leaves fairsub's default), a
boolean for a switch, a file path for an option that names a file, and a text field otherwise
(its words go to fairsub as typed; an empty field leaves the default). fairsub checks every
value and its message is the operator's error. The OpenSubdiv options that the add-on sets
from Blender's own settings (boundary, crease method, face-varying interpolation, smooth
triangles) have dedicated properties in the operator; ``creases`` (a side file of tags) is
replaced by the mesh's crease attributes."""

import fairsub

#: Options the operator sets itself (from its own properties or the mesh), not through the
#: generic ``opt_`` properties.
OWN = {"boundary", "crease-method", "fvar", "smooth-triangles", "creases"}

_cache = {}


def schemes():
    """The catalogue rows (``fairsub.schemes()``), read once."""
    if "schemes" not in _cache:
        _cache["schemes"] = fairsub.schemes()
    return _cache["schemes"]


def options(scheme):
    """The options of ``scheme`` (``fairsub.scheme_options``), read once per scheme."""
    key = ("options", scheme)
    if key not in _cache:
        _cache[key] = fairsub.scheme_options(scheme)
    return _cache[key]


def scheme(name):
    """The catalogue row of a scheme."""
    for s in schemes():
        if s["name"] == name:
            return s
    raise ValueError(f"fairsub has no scheme '{name}'")


def takes(name, option):
    """Whether scheme ``name`` takes ``option`` (its command-line name, ``boundary``)."""
    return any(o["name"] == option for o in options(name))


def scheme_items():
    """The scheme menu: (identifier, label, description) per scheme, in catalogue order. The
    strings live in the cache, as Blender wants for enum items."""
    if "items" not in _cache:
        items = []
        for s in schemes():
            what = []
            if s["refine"]:
                what.append("levels")
            if s["rings"]:
                what.append("exact surface")
            desc = f"{s['family']}; {s['smoothness']}; input: {s['input']} ({', '.join(what)})"
            items.append((s["name"], s["name"], desc))
        _cache["items"] = items
    return _cache["items"]


def generic_options():
    """Every option of every scheme that goes through an ``opt_`` property, once each, in
    catalogue order."""
    seen = {}
    for s in schemes():
        for o in options(s["name"]):
            if o["name"] not in OWN and o["name"] not in seen:
                seen[o["name"]] = o
    return list(seen.values())


def prop_name(option):
    """The Blender property of an option: ``split-ratio`` -> ``opt_split_ratio``."""
    return "opt_" + option.replace("-", "_")


def make_property(bpy_props, o):
    """The Blender property for option ``o`` (see the module documentation)."""
    desc = o["help"] or o["name"]
    if o["choices"] and not o["flag"]:
        items = [("DEFAULT", "Default", "fairsub's default")]
        items += [(c, c, f"--{o['name']} {c}") for c in o["choices"]]
        return bpy_props.EnumProperty(name=o["name"], description=desc, items=items)
    if o["flag"]:
        return bpy_props.BoolProperty(name=o["name"], description=desc, default=False)
    if o["file"]:
        return bpy_props.StringProperty(name=o["name"], description=desc, subtype="FILE_PATH")
    if o["repeated"]:
        desc += " (several values separated by spaces)"
    return bpy_props.StringProperty(name=o["name"], description=desc)


def option_keywords(props, scheme_name):
    """The keyword options of ``fairsub.subdivide`` / ``surface`` for the ``opt_`` properties
    of ``props`` that scheme ``scheme_name`` takes (those left at their default are left
    out)."""
    kw = {}
    for o in options(scheme_name):
        if o["name"] in OWN:
            continue
        value = getattr(props, prop_name(o["name"]), None)
        key = o["name"].replace("-", "_")
        if o["flag"]:
            if value:
                kw[key] = True
        elif o["choices"]:
            if value and value != "DEFAULT":
                kw[key] = value
        elif isinstance(value, str) and value.strip():
            words = value.split()
            kw[key] = words if o["repeated"] else value.strip()
    return kw
