"""The template library: class prototypes (small PNGs) and labelled feature examples (index.json).

Built by `assistbot templates` from scenes of the "library" seed stream (never scored).  For
each classified thing (the bottle's state, the glass's state, the hand's posture, whether the
hand is held out to the robot) the library keeps, per class, up to `PROTOTYPES` prototype
templates (means of k-means clusters of the examples' crops) and the examples' feature vectors.
Classification of a new crop: `cv2.matchTemplate` (normalised correlation coefficient) of the
crop against every prototype gives one score per class; those scores and the shape features
form the feature vector, classified by its nearest labelled examples (k-NN, standardised
features), or for the hand (`MLP_KINDS`) by a small network trained on them.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

import cv2
import numpy as np

from assistbot import catalogue
from assistbot.errors import UserError
from assistbot.resources import TEMPLATES
from assistbot.task import HAND_POSTURES

PROTOTYPES = 2
#: what is classified, and its classes: each task object's states, the hand's postures
KINDS = {**catalogue.STATES, "hand": HAND_POSTURES}
#: whether the hand seen is held out toward the robot, learnt from the hand's features like its posture:
#: where and how a person holds things out differs with the body and the habit (short arms, a seat
#: farther back hold out short of the hand-over zone), which one place on the table cannot tell
HELD_OUT = "held_out"
#: every classifier the library holds, and its classes
CLASSES = {**KINDS, HELD_OUT: ("kept", "held_out")}
K_NEIGHBOURS = 5


_SHIFT = 3
_MOSAICS: dict[int, tuple] = {}


def _mosaic_entry(protos: list[list[np.ndarray]]) -> tuple:
    """The mosaic (image, class per prototype, stride), the prototypes, and the gather indices of
    the score map: the columns of each prototype's shifts (prototype-major) and, per class, its
    prototypes' entries in the per-prototype maxima and the extra -1 entry at the end (the floor)."""
    key = id(protos)
    if key not in _MOSAICS:
        flat = [(c, p) for c, plist in enumerate(protos) for p in plist]
        h, w = flat[0][1].shape
        stride = w + 2 * _SHIFT
        img = np.zeros((h + 2 * _SHIFT, len(flat) * stride), np.float32)
        for j, (_, p) in enumerate(flat):
            img[_SHIFT:_SHIFT + h, j * stride + _SHIFT:j * stride + _SHIFT + w] = p
        n = len(flat)
        cols = ((np.arange(n) * stride)[:, None] + np.arange(2 * _SHIFT + 1)[None]).ravel()
        cls = np.array([c for c, _ in flat])
        width = max(len(pl) for pl in protos) + 1     # + the -1 floor, as the scores start at -1
        group = np.full((len(protos), width), n)
        for c in range(len(protos)):
            idx = np.flatnonzero(cls == c)
            group[c, :idx.size] = idx
        # protos kept: the id stays theirs
        _MOSAICS[key] = (img, cls, stride, protos, (cols, group))
    return _MOSAICS[key]


def template_scores(crop: np.ndarray | None, protos: list[list[np.ndarray]]) -> np.ndarray:
    """Best normalised match (cv2.matchTemplate, TM_CCOEFF_NORMED, +-3 px shifts) of crop against each
    class's prototypes: one score per class, in ONE matchTemplate call (the crop slides over a
    mosaic of all prototypes).  Crops are normalised to the template size by the detector (their
    size follows the object's distance), so one scale suffices.  A non-finite score counts as -1."""
    if crop is None or not any(protos):
        return np.zeros(0, np.float32)
    img, cls, stride, _, (cols, group) = _mosaic_entry(protos)
    r = cv2.matchTemplate(img, crop.astype(np.float32, copy=False), cv2.TM_CCOEFF_NORMED)
    n = len(cls)
    if r.shape[1] > cols[-1]:
        # only the shifts' columns, gathered at once (the usual case: a crop of the templates' size)
        sub = r[:, cols]
        if np.isfinite(sub).all():
            per = np.empty(n + 1, np.float32)
            per[n] = -1.0
            per[:n] = sub.reshape(r.shape[0], n, 2 * _SHIFT + 1).max(axis=(0, 2))
            return per[group].max(axis=1)
    r = np.nan_to_num(r, nan=-1.0, posinf=-1.0, neginf=-1.0)
    r = np.pad(r, ((0, 0), (0, max(0, n * stride - r.shape[1]))), constant_values=-1.0)
    per = r[:, :n * stride].reshape(r.shape[0], n, stride)[:, :, :2 * _SHIFT + 1].max(axis=(0, 2))
    out = np.full(len(protos), -1.0, np.float32)
    np.maximum.at(out, cls, per)
    return out


def kmeans(X: np.ndarray, k: int, seed: int = 0, iters: int = 20) -> np.ndarray:
    """Deterministic k-means (farthest-point init from a seeded first pick); returns labels."""
    rng = np.random.default_rng(seed)
    k = min(k, len(X))
    centres = [X[rng.integers(len(X))]]
    for _ in range(1, k):
        d = np.min([np.sum((X - c) ** 2, axis=1) for c in centres], axis=0)
        centres.append(X[int(np.argmax(d))])
    C = np.array(centres)
    lab = np.zeros(len(X), int)
    for _ in range(iters):
        lab = np.argmin(((X[:, None, :] - C[None]) ** 2).sum(-1), axis=1)
        C = np.array([X[lab == j].mean(0) if np.any(lab == j) else C[j] for j in range(k)])
    return lab


@dataclass
class Classifier:
    """Prototypes and examples of one kind ("bottle", "glass" or "hand")."""

    kind: str
    classes: tuple[str, ...]
    protos: list[list[np.ndarray]]
    X: np.ndarray           # examples' feature vectors (standardised)
    y: np.ndarray           # class index per example
    mean: np.ndarray
    std: np.ndarray
    weights: np.ndarray
    mlp: dict[str, np.ndarray] | None = None     # W1, b1, W2, b2: a one-hidden-layer network instead of k-NN

    def features(self, crop: np.ndarray | None, extra: np.ndarray) -> np.ndarray:
        return np.concatenate([template_scores(crop, self.protos), np.asarray(extra, np.float32)])

    def classify(self, crop: np.ndarray | None, extra: np.ndarray) -> tuple[str, float, np.ndarray]:
        """(class, confidence in [0, 1], class template scores)."""
        pr, f = self.probabilities(crop, extra)
        c = int(pr.argmax())
        return self.classes[c], float(pr[c]), f[:len(f) - len(extra)]

    def probabilities(self, crop: np.ndarray | None, extra: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(each class's probability, or share of the neighbours' weighted votes; the feature vector)."""
        f = self.features(crop, extra)
        z = (f - self.mean) / self.std * self.weights
        if self.mlp is not None:   # an ensemble: the members' probabilities averaged
            m = self.mlp
            h = np.tanh(np.einsum("f,mfh->mh", z, m["W1"]) + m["b1"])
            logit = np.einsum("mh,mhc->mc", h, m["W2"]) + m["b2"]
            pr = np.exp(logit - logit.max(axis=1, keepdims=True))
            pr = pr / pr.sum(axis=1, keepdims=True)
            return pr.sum(axis=0) / len(pr), f      # .mean(axis=0): the same sum and division
        d = np.sum((self.X - z) ** 2, axis=1)
        idx = np.argpartition(d, min(K_NEIGHBOURS, len(d) - 1))[:K_NEIGHBOURS]
        w = 1.0 / (np.sqrt(d[idx]) + 1e-3)
        votes = np.bincount(self.y[idx], weights=w, minlength=len(self.classes))
        return votes / votes.sum(), f


def build_classifier(kind: str, crops: list[np.ndarray | None], extras: list[np.ndarray], labels: list[str], seed: int = 0,
                     weights: np.ndarray | None = None) -> Classifier:
    classes = CLASSES[kind]
    y = np.array([classes.index(lab) for lab in labels])
    protos = []
    for c in range(len(classes)):
        sel = [cr for cr, yy in zip(crops, y) if yy == c and cr is not None]
        if not sel:
            protos.append([])
            continue
        X = np.array([s.ravel() for s in sel])
        lab = kmeans(X, PROTOTYPES, seed + c)
        protos.append([_to_u8(X[lab == j].mean(0).reshape(sel[0].shape)) for j in range(lab.max() + 1) if np.any(lab == j)])
    protos_f = [[p.astype(np.float32) / 255.0 for p in pl] for pl in protos]
    F = np.array([np.concatenate([template_scores(cr, protos_f), e]) for cr, e in zip(crops, extras)], np.float32)
    mean, std = F.mean(0), F.std(0) + 1e-3
    w = np.ones(F.shape[1], np.float32)
    if weights is not None:
        w[len(w) - len(weights):] = weights      # weights of the shape features (template scores weigh 1)
    Z = (F - mean) / std * w
    mlp = None
    if kind in MLP_KINDS:
        members = [train_mlp(Z, y, len(classes), seed * 100 + j) for j in range(MLP_MEMBERS)]
        mlp = {k: np.stack([m[k] for m in members]) for k in members[0]}
    if mlp is not None:
        Z = Z[:0]                  # the network replaces the examples (their labels stay, for the counts)
    return Classifier(kind, classes, protos_f, Z, y, mean, std, w, mlp)


MLP_KINDS = ("hand", HELD_OUT)
MLP_HIDDEN, MLP_EPOCHS, MLP_RATE, MLP_DECAY = 64, 3000, 0.5, 3e-3
MLP_MEMBERS = 3             # networks from different seeds, averaged: a steadier fit than one


def train_mlp(Z: np.ndarray, y: np.ndarray, n_classes: int, seed: int = 0) -> dict[str, np.ndarray]:
    """A tanh network with one hidden layer, softmax output, full-batch gradient descent with weight
    decay (deterministic for a seed); weights rounded as they are stored."""
    rng = np.random.default_rng(seed)
    Z = Z.astype(np.float64)
    W1 = rng.normal(0, 1 / np.sqrt(Z.shape[1]), (Z.shape[1], MLP_HIDDEN))
    b1 = np.zeros(MLP_HIDDEN)
    W2 = rng.normal(0, 1 / np.sqrt(MLP_HIDDEN), (MLP_HIDDEN, n_classes))
    b2 = np.zeros(n_classes)
    Y = np.eye(n_classes)[y]
    for _ in range(MLP_EPOCHS):
        h = np.tanh(Z @ W1 + b1)
        z = h @ W2 + b2
        z -= z.max(1, keepdims=True)
        p = np.exp(z)
        p /= p.sum(1, keepdims=True)
        g = (p - Y) / len(Z)
        gh = g @ W2.T * (1 - h ** 2)
        W2 -= MLP_RATE * (h.T @ g + MLP_DECAY * W2)
        b2 -= MLP_RATE * g.sum(0)
        W1 -= MLP_RATE * (Z.T @ gh + MLP_DECAY * W1)
        b1 -= MLP_RATE * gh.sum(0)
    return {k: np.round(v, 5).astype(np.float32) for k, v in (("W1", W1), ("b1", b1), ("W2", W2), ("b2", b2))}


def _to_u8(a: np.ndarray) -> np.ndarray:
    return np.clip(np.round(a * 255.0), 0, 255).astype(np.uint8)


# ---------------------------------------------------------------------------- files
def save(root: Path, classifiers: dict[str, Classifier], calibration: dict, meta: dict) -> list[Path]:
    root.mkdir(parents=True, exist_ok=True)
    written = []
    index = {"version": 1, **meta, "kinds": {}}
    for kind, clf in classifiers.items():
        entry = {"classes": list(clf.classes), "prototypes": {}, "mean": _r(clf.mean), "std": _r(clf.std),
                 "weights": _r(clf.weights), "examples": {"X": [_r(x) for x in clf.X], "y": clf.y.tolist()}}
        if clf.mlp is not None:
            entry["mlp"] = {k: [[_r(row) for row in np.atleast_2d(member)] for member in v] for k, v in clf.mlp.items()}
        for c, plist in zip(clf.classes, clf.protos):
            names = []
            for j, p in enumerate(plist):
                name = f"{kind}_{c}_{j}.png"
                cv2.imwrite(str(root / name), _to_u8(p))
                written.append(root / name)
                names.append(name)
            entry["prototypes"][c] = names
        index["kinds"][kind] = entry
    (root / "index.json").write_text(json.dumps(index, indent=1, sort_keys=True) + "\n")
    (root / "calibration.json").write_text(json.dumps(calibration, indent=1, sort_keys=True) + "\n")
    return written + [root / "index.json", root / "calibration.json"]


def _r(a) -> list[float]:
    return [round(float(v), 5) for v in np.asarray(a).ravel()]


def load_calibration(root: Path | None = None) -> dict:
    path = (root or TEMPLATES) / "calibration.json"
    if not path.exists():
        raise UserError(str(path), "calibration",
                        "missing colour calibration; run `assistbot calibrate` (or `assistbot templates`, which also calibrates)")
    return json.loads(path.read_text())


def load(root: Path | None = None) -> tuple[dict[str, Classifier], dict]:
    """The classifiers and the calibration from assets/templates/ (UserError if missing)."""
    root = root or TEMPLATES
    path = root / "index.json"
    if not path.exists():
        raise UserError(str(path), "template library", "missing; run `assistbot templates` to build it")
    index = json.loads(path.read_text())
    out = {}
    for kind, e in index["kinds"].items():
        protos = [[cv2.imread(str(root / n), cv2.IMREAD_GRAYSCALE).astype(np.float32) / 255.0 for n in e["prototypes"].get(c, [])]
                  for c in e["classes"]]
        X = np.array(e["examples"]["X"], np.float32)
        mlp = None
        if "mlp" in e:
            mlp = {k: np.array(v, np.float32) for k, v in e["mlp"].items()}
            mlp["b1"], mlp["b2"] = mlp["b1"][:, 0], mlp["b2"][:, 0]     # (members, units)
        out[kind] = Classifier(kind, tuple(e["classes"]), protos, X, np.array(e["examples"]["y"], int),
                               np.array(e["mean"], np.float32), np.array(e["std"], np.float32), np.array(e["weights"], np.float32), mlp)
    return out, load_calibration(root)
