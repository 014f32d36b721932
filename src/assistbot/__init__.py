"""assistbot: a MuJoCo simulation of a pro-active assistant robot driven by dynamic neural fields."""

__version__ = "0.1.0"
