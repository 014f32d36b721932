"""Scenario texts shared by benchmarks (run as scripts, so benchmarks/ is on sys.path)."""

#: fig5's arrangement with a passive person, cut to ``t`` simulated seconds (``.format(name=..., t=...)``)
FIG5_LIKE = """\
name: {name}
seed: 0
time_limit: {t}
objects:
  bottle: {{zone: RWS, state: closed}}
  glass: {{zone: HWS, state: empty}}
human:
  profile: passive
"""
