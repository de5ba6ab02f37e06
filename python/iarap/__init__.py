"""As-rigid-as-possible surface deformation with the iARAP discretization.

The functions and classes are those of the compiled extension iarap._core; this package adds the type
stubs (__init__.pyi, py.typed) and names them as members of `iarap` (repr, pickling, error messages).
"""
import os as _os

# The library's OpenMP threads sleep while they wait instead of spinning, as in the iarap tool
# (app/omp_wait_policy.cpp), unless the user chose a policy: on a busy machine a spinning thread takes the
# core the thread it waits for needs (measured under load: a 2-thread solve took 0.65 to 9.2 s spinning,
# 0.57 to 0.64 s passive; issue 43). libgomp reads the variable once, when it is loaded, which is when the
# extension below is: a process that loaded libgomp before importing iarap keeps the policy it started with.
_os.environ.setdefault("OMP_WAIT_POLICY", "passive")
del _os

from . import _core  # noqa: E402
from ._core import *  # noqa: F401,F403,E402  (the public names of the extension, none starting with "_")
from ._core import __version__  # noqa: F401,E402

__doc__ = _core.__doc__

for _name in dir(_core):
    _member = getattr(_core, _name)
    if isinstance(_member, type) and getattr(_member, "__module__", "") == _core.__name__:
        _member.__module__ = __name__
del _name, _member
