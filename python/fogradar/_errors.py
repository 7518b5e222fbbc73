"""fogradar's bad-input error."""


class InvalidParameter(ValueError):
    """Bad input: the message word for word as `fogradar` prints it after "fogradar: ", the key
    or option as the user wrote it (``key``), and for a scenario file or text the line the message
    points at (``line``, else None)."""

    def __init__(self, message, key=None, line=None):
        super().__init__(message)
        self.key = key
        self.line = line
