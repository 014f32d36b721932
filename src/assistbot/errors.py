"""The one error type for mistakes a user can make.

Every such mistake (a bad scenario file, an unknown parameter, a missing GL
backend) ends in a single line ``error: <where>: <key>: <message>`` and exit
status 2; `assistbot.cli` prints it. Library code raises `UserError` and never
prints or exits itself.
"""

from __future__ import annotations


class UserError(Exception):
    """A mistake the user can fix: names where it is, which key, and what is allowed."""

    def __init__(self, where: str, key: str, message: str) -> None:
        self.where = str(where)
        self.key = str(key)
        self.message = str(message)
        super().__init__(self.line())

    def line(self) -> str:
        # one line whatever the message quotes (a YAML parser's report spans several)
        return " ".join(f"error: {self.where}: {self.key}: {self.message}".split())


def read_yaml(path, what: str = "file"):
    """Parse a user's YAML file; an unreadable file or bad YAML is a `UserError` naming the file (and line)."""
    from pathlib import Path

    import yaml

    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as exc:
        raise UserError(str(path), "-", f"cannot read the {what}: {exc.strerror}") from None
    except UnicodeDecodeError as exc:
        raise UserError(str(path), f"byte {exc.start}", "not a text file (UTF-8 expected)") from None
    try:
        return yaml.safe_load(text)
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        at = f"line {mark.line + 1}" if mark else "-"
        raise UserError(str(path), at, f"not valid YAML: {getattr(exc, 'problem', exc)}") from None
