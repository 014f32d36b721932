"""The error of `assistbot.fields`: names the field (or coupling) and the parameter."""

from __future__ import annotations


class FieldError(ValueError):
    """A bad field, kernel, coupling or network parameter.

    ``where`` names the element (``field 'ASL'``, ``coupling 'OL->ASL'``,
    ``network``), ``key`` the parameter, ``message`` what is wrong and what is
    allowed.
    """

    def __init__(self, where: str, key: str, message: str) -> None:
        self.where = where
        self.key = key
        self.message = message
        super().__init__(self.line())

    def line(self) -> str:
        return f"error: {self.where}: {self.key}: {self.message}"
