"""Errors the bridge reports to its client, each with a message a user can act on."""


class BridgeError(Exception):
    """An error with a machine-readable type name."""

    type_name = "internal"

    def __init__(self, message):
        super().__init__(message)
        self.message = message


class BadRequest(BridgeError):
    """The request is malformed (unknown op, missing or wrong arguments)."""

    type_name = "bad_request"


class FileMissing(BridgeError):
    """A file named in the request does not exist."""

    type_name = "file_missing"


class ModelError(BridgeError):
    """Drake could not parse or finalize the models."""

    type_name = "model_error"
