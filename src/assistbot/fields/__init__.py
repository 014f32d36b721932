"""assistbot.fields: Amari dynamic neural fields (Dynamic Field Theory), numpy/scipy only.

Equations (the seed's section III.A):

- (1) tau du/dt = -u + S(x, t) + integral w(x - x') f(u(x', t)) dx' + h, h < 0
- (2) w(d) = A exp(-d^2 / 2 sigma^2) - w_inhib
- (3) f(u) = 1 / (1 + exp(-beta (u - u0)))
- (4) S(x, t) = k sum_m sum_j a_mj c_j(t) exp(-(x - x_m)^2 / 2 sigma^2),
  c_j the presence of a self-stabilised peak at item j of the source.

A `Network` is declared as data (`Network.from_dict` / `from_yaml`), stepped
as one batch (numba when available, numpy otherwise), addressed by field,
item and parameter path, and recorded for paper-style plots. Its fields are
1-D or 2-D (``shape``); they couple through items (eq. 4) or continuously
(a Gaussian kernel over a source's whole output, projected between 1-D and
2-D by sum, max or expansion), as the DFT toolkits cedar and COSIVINA do.
Fields may keep a memory trace (a slowly built preshape) and item couplings
may learn their table by a gated Hebbian rule (`MemorySpec`, `LearnSpec`).
Nothing here knows robots.
"""

from assistbot.fields.errors import FieldError
from assistbot.fields.network import Network, format_table
from assistbot.fields.plot import plot_history
from assistbot.fields.record import Recorder
from assistbot.fields.spec import (
    ContinuousCouplingSpec,
    CouplingSpec,
    FieldSpec,
    KernelSpec,
    LearnSpec,
    MemorySpec,
    NetworkSpec,
)

__all__ = [
    "ContinuousCouplingSpec",
    "CouplingSpec",
    "FieldError",
    "FieldSpec",
    "KernelSpec",
    "LearnSpec",
    "MemorySpec",
    "Network",
    "NetworkSpec",
    "Recorder",
    "format_table",
    "plot_history",
]
