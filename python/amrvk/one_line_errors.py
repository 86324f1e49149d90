"""Wrong argument types are one line naming the keyword (issue 33, point 4), for every call of the
compiled module that does not check its arguments itself: pybind11 answers a type it cannot
convert with a multi-line "incompatible function arguments" listing the signatures. Each public
function, method and constructor of ``amrvk._amrvk`` is wrapped: such a TypeError becomes
``TypeError: NAME: expected TYPE, got VALUE`` for the first argument whose type does not fit the
signature pybind11 states, or one line with the signature where none can be singled out.
"""
import functools
import numbers
import os
import re

_SIGNATURE = re.compile(r"^\s*1\. (?:[\w.]+)?\((.*)\)(?: -> .*)?$", re.M)


def _parameters(signature):
    """[(name, type text)] of 'a: int, b: List[float] = [0.0], **kwargs' (self and ** dropped)."""
    out, depth, current = [], 0, ""
    for ch in signature + ",":
        if ch in "[(":
            depth += 1
        elif ch in "])":
            depth -= 1
        if ch == "," and depth == 0:
            part = current.strip()
            current = ""
            if not part or part.startswith("*") or part.startswith("self"):
                continue
            name, _, rest = part.partition(":")
            out.append((name.strip(), rest.split("=")[0].strip()))
        else:
            current += ch
    return out


def _fits(value, kind):
    if kind.startswith("Optional["):
        return value is None or _fits(value, kind[len("Optional["):-1])
    if kind in ("object", ""):
        return True
    if kind == "str":
        return isinstance(value, str)
    if kind == "os.PathLike":
        return isinstance(value, (str, os.PathLike))
    if kind == "bool":
        return isinstance(value, bool)
    if kind == "int":
        return isinstance(value, numbers.Integral) and not isinstance(value, bool)
    if kind == "float":
        return isinstance(value, numbers.Real) and not isinstance(value, bool)
    if kind.startswith("List[") or kind.startswith("Tuple["):
        return hasattr(value, "__len__") and not isinstance(value, (str, bytes))
    if kind.startswith("amrvk._amrvk."):
        return type(value).__name__ == kind.rsplit(".", 1)[1]
    return True


def _expected(kind):
    if kind.startswith("Optional["):
        return _expected(kind[len("Optional["):-1]) + " or None"
    if kind.startswith("List["):
        return "a list of " + {"int": "whole numbers", "float": "numbers"}.get(kind[5:-1], kind[5:-1])
    return {"str": "a string", "os.PathLike": "a path (str or os.PathLike)", "bool": "True or False",
            "int": "a whole number", "float": "a number"}.get(kind, kind.replace("amrvk._amrvk.", "an amrvk."))


def _shown(value):
    """A value as one short line: its repr, or its type where the repr is long or spans lines
    (a numpy array's)."""
    shown = repr(value)
    return shown if len(shown) <= 60 and "\n" not in shown else f"a {type(value).__name__}"


def _one_line(qualname, message, args, kwargs):
    found = _SIGNATURE.search(message)
    if found is None:
        return None
    parameters = _parameters(found.group(1))
    if len(args) > len(parameters) and "*args" not in found.group(1):
        names = ", ".join(n for n, _ in parameters)
        return f"{qualname}: takes {len(parameters)} argument(s) ({names}), got {len(args)}"
    given = list(zip([n for n, _ in parameters], args)) + [(k, v) for k, v in kwargs.items()]
    kinds = dict(parameters)
    for name, value in given:
        # A path or name with a NUL character: no file system or C string takes one.
        if name in kinds and isinstance(value, str) and "\0" in value:
            return f"{name}: contains a NUL character (at {value.index(chr(0))}) in {_shown(value)}"
        if name in kinds and not _fits(value, kinds[name]):
            return f"{name}: expected {_expected(kinds[name])}, got {_shown(value)}"
    names = ", ".join(n for n, _ in parameters)
    return f"{qualname}: the arguments do not fit its parameters ({names})"


def _wrap(function, qualname, skip_self):
    @functools.wraps(function)
    def call(*args, **kwargs):
        try:
            return function(*args, **kwargs)
        except TypeError as e:
            text = str(e)
            line = None
            if "incompatible" in text and "\n" in text:
                line = _one_line(qualname, text, args[1:] if skip_self else args, kwargs)
            # A failed __init__'s self is half made: no traceback frame may keep it reachable.
            args = kwargs = None
            if line is None:
                raise
            raise TypeError(line) from None
        except BaseException:
            args = kwargs = None
            raise

    return call


def wrap_function(function, qualname):
    """A module-level function of the compiled module, wrapped as the methods are."""
    return _wrap(function, qualname, False)


def _made(function, qualname, initialized):
    """`function(self, ...)` refusing a self that __init__ never filled (T.__new__(T) alone): pybind11
    would call the C++ method on a null object and crash the interpreter."""

    @functools.wraps(function)
    def call(self, *args, **kwargs):
        if not initialized(self):
            raise TypeError(f"{qualname}: this {type(self).__name__} was never initialised "
                            f"(made by __new__ without __init__)")
        return function(self, *args, **kwargs)

    return call


# Dunder methods of the bound classes that take an initialised self.
_DUNDERS = ("__repr__", "__str__", "__eq__", "__hash__", "__enter__", "__exit__", "__getstate__")


def install(classes, initialized):
    """Wraps the classes' constructors, methods and static methods; every method, dunder method and
    property of an instance first asks `initialized(self)`."""
    for cls in classes:
        for name, attr in list(vars(cls).items()):
            qualname = f"{cls.__name__}()" if name == "__init__" else f"{cls.__name__}.{name}"
            if isinstance(attr, property):
                fset = attr.fset and _made(attr.fset, qualname, initialized)
                setattr(cls, name, property(_made(attr.fget, qualname, initialized), fset, attr.fdel, attr.__doc__))
                continue
            if name.startswith("_") and name != "__init__" and name not in _DUNDERS:
                continue
            if isinstance(attr, staticmethod):
                setattr(cls, name, staticmethod(_wrap(attr.__func__, qualname, False)))
            elif type(attr).__name__ == "instancemethod":  # pybind11's methods and constructors
                wrapped = _wrap(attr.__func__, qualname, True)
                setattr(cls, name, wrapped if name == "__init__" else _made(wrapped, qualname, initialized))
