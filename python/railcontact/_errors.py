"""railcontact's exception classes, one per error kind of the library (docs/PYTHON.md "Errors").

Every error of the library is a RailcontactError; the class says what went wrong, as the C API's
status (docs/C_API.md) and the C++ ErrorKind do.
"""


class RailcontactError(Exception):
    """Base class of every error railcontact raises."""


class InvalidInputError(RailcontactError, ValueError):
    """A value or option outside what is allowed (also NaN, infinity). Status RC_INVALID_INPUT."""


class NoContactError(RailcontactError):
    """The bodies do not touch. Status RC_NO_CONTACT."""


class SeveralPatchesError(RailcontactError):
    """Several contact patches where the computation needs one. Status RC_SEVERAL_PATCHES."""


class NotConvergedError(RailcontactError, RuntimeError):
    """An iterative solver did not reach its tolerance. Status RC_NOT_CONVERGED."""


class RailcontactIOError(RailcontactError, OSError):
    """A file cannot be read or written. Status RC_IO."""


class InternalError(RailcontactError, RuntimeError):
    """An invariant of railcontact does not hold: a bug, please report it. Status RC_INTERNAL."""


class CancelledError(RailcontactError):
    """A progress callback stopped a flexibility-table build. Status RC_CANCELLED."""


__all__ = ["RailcontactError", "InvalidInputError", "NoContactError", "SeveralPatchesError", "NotConvergedError",
           "RailcontactIOError", "InternalError", "CancelledError"]
