"""The one error type for bad input: a single line naming file, key and place.

The CLI prints it as ``swarmvm: error: <line>`` and exits with status 2; nothing is written."""


class InputError(Exception):
    """Bad input. ``where`` names the supervisor / state / event concerned, if any."""

    def __init__(self, file, key, message, where=""):
        super().__init__(message)
        self.file, self.key, self.where, self.message = file, key, where, message

    def __str__(self):
        parts = [self.file, self.key, self.where, self.message]
        return ": ".join(part for part in parts if part)
