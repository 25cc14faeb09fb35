"""The error metrics and display transform the evaluation scripts share.

relMSE is Rousselle et al.'s, as `statmc --compare` computes it: the mean over pixels and
channels of (x - r)^2 / (r^2 + 0.01)."""

import numpy as np

EPS = 0.01


def relmse(x, reference, trim=0.0):
    """relMSE of `x` against `reference`; `trim` drops that share of the largest
    pixel-channel errors (a few fireflies decide short renders)."""
    e = ((x - reference) ** 2 / (reference ** 2 + EPS)).ravel()
    if trim > 0:
        e = np.sort(e)[: int(len(e) * (1 - trim))]
    return float(np.mean(e))


def tonemap(x):
    """Reinhard, then gamma 2.2, in [0, 1]."""
    return np.clip(x / (1 + x), 0, 1) ** (1 / 2.2)
