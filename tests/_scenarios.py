"""Scenario texts shared by tests (imported by test modules; pytest puts tests/ on sys.path)."""

#: a short passive-user scenario: a few wall seconds per episode, for tests of the machinery around episodes
TINY = """\
name: tiny
seed: 0
time_limit: 3
objects:
  bottle: {zone: RWS, state: closed}
  glass: {zone: HWS, state: empty}
human:
  profile: passive
"""
