"""As-rigid-as-possible surface deformation with the iARAP discretization.

The functions and classes are those of the compiled extension iarap._core; this package adds the type
stubs (__init__.pyi, py.typed) and names them as members of `iarap` (repr, pickling, error messages).
"""
from . import _core
from ._core import *  # noqa: F401,F403  (the public names of the extension, none starting with "_")
from ._core import __version__  # noqa: F401

__doc__ = _core.__doc__

for _name in dir(_core):
    _member = getattr(_core, _name)
    if isinstance(_member, type) and getattr(_member, "__module__", "") == _core.__name__:
        _member.__module__ = __name__
del _name, _member
