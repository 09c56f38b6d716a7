"""Every public function, class, method and property of the module has a docstring that says more than its
signature, and those that take or return arrays state the shape (docs/python.md: units, shapes and dtypes)."""
import inspect
import re

import radwalk

# A shape as the docstrings write it: (N, 3), (N,), (F, 3), (V, 3), (height, width, 3), (r, g, b), (n, 4), ...
SHAPE = re.compile(r"\((?:[A-Za-z0-9_+ -]+, )+[A-Za-z0-9_+ -]*\)|\([A-Za-z0-9_]+,\)")
# Arguments that take arrays although pybind11's signature says `object`: numpy arrays, scipy matrices or lists.
ARRAY_ARGUMENTS = {"vertices", "faces", "rho", "emission", "F", "response", "fields", "Ke", "camera", "patches",
                   "mesh", "values"}


def public_members():
    """(qualified name, object, owner class or None) of every public member of the module and of its classes."""
    for name, obj in vars(radwalk).items():
        if name.startswith("_"):
            continue
        yield f"radwalk.{name}", obj, None
        if inspect.isclass(obj):
            for attr, member in vars(obj).items():
                if attr.startswith("_") and attr not in ("__init__", "__len__", "__getitem__", "__iter__"):
                    continue
                if attr == "__init__" and "pybind11_object.__init__" in (getattr(member, "__qualname__", "") or ""):
                    continue
                yield f"radwalk.{name}.{attr}", member, obj


def callable_of(obj):
    """The function behind a member: the getter of a property, the function of a static method, else obj."""
    if isinstance(obj, property):
        return obj.fget
    if isinstance(obj, staticmethod):
        return obj.__func__
    return obj


def body(doc, name):
    """The docstring without pybind11's signature lines ("name(arg: type, ...) -> type")."""
    short = name.rsplit(".", 1)[-1]
    lines = [l for l in (doc or "").splitlines()
             if not re.match(rf"^\s*(\d+\. )?{re.escape(short)}\(.*\)( -> .*)?$", l)
             and l.strip() != "Overloaded function."]
    return "\n".join(lines).strip()


def signature_text(obj, name):
    short = name.rsplit(".", 1)[-1]
    fn = callable_of(obj)
    doc = getattr(fn, "__doc__", "") or ""
    return "\n".join(l for l in doc.splitlines() if re.match(rf"^\s*(\d+\. )?{re.escape(short)}\(", l)
                     or (isinstance(obj, property) and re.match(r"^\s*\(self", l)))


def takes_or_returns_arrays(obj, name):
    sig = signature_text(obj, name)
    if not sig:
        fn = callable_of(obj)
        sig = (getattr(fn, "__doc__", "") or "").splitlines()[0] if getattr(fn, "__doc__", None) else ""
    if "ndarray" in sig:
        return True
    params = re.findall(r"(\w+): ", sig)
    return any(p in ARRAY_ARGUMENTS for p in params)


def documentation(obj):
    if isinstance(obj, property):
        return obj.__doc__ or ""
    return callable_of(obj).__doc__ or ""


def test_every_public_callable_has_a_docstring_beyond_its_signature():
    missing = []
    for name, obj, _ in public_members():
        if not (callable(obj) or isinstance(obj, (property, staticmethod))):
            continue
        if len(body(documentation(obj), name)) < 20:
            missing.append(name)
    assert not missing, "without a docstring beyond the signature: " + ", ".join(missing)


def test_docstrings_of_array_functions_state_the_shape():
    vague = []
    for name, obj, _ in public_members():
        if inspect.isclass(obj) or not (callable(obj) or isinstance(obj, (property, staticmethod))):
            continue
        if takes_or_returns_arrays(obj, name) and not SHAPE.search(body(documentation(obj), name)):
            vague.append(name)
    assert not vague, "taking or returning arrays without a shape in the docstring: " + ", ".join(vague)


def test_the_walk_finds_what_it_should():
    """The walk itself: it sees the module's functions, the classes' methods and properties, and it flags a
    callable without a docstring (a test that cannot fail is a defect)."""
    names = {name for name, _, _ in public_members()}
    for expected in ("radwalk.load", "radwalk.Scene.from_arrays", "radwalk.Scene.rho", "radwalk.Result.B",
                     "radwalk.Result.to_meshio", "radwalk.Scene.from_meshio", "radwalk.solve"):
        assert expected in names, expected
    assert takes_or_returns_arrays(vars(radwalk.Scene)["areas"], "radwalk.Scene.areas")
    assert takes_or_returns_arrays(radwalk.Scene.from_arrays, "radwalk.Scene.from_arrays")

    def bare(x):
        return x

    assert body(bare.__doc__, "bare") == ""
    assert not SHAPE.search("Radiosity per patch in W per unit length squared.")
    assert SHAPE.search("B (N, 3): radiosity") and SHAPE.search("areas (N,) float64")
