"""The template library: class prototypes (small PNGs) and labelled feature examples (index.json).

Built by `assistbot templates` from scenes of the "library" seed stream (never scored).  For
each classified thing — the bottle's state, the glass's state, the hand's posture — the
library keeps, per class, up to `PROTOTYPES` prototype templates (means of k-means clusters
of the examples' crops) and the examples' feature vectors.  Classification of a new crop:
the normalised correlation coefficient (cv2.matchTemplate's TM_CCOEFF_NORMED, computed as one
matrix-vector product with the prototypes' precomputed shifted windows) of the crop against every
prototype, shifted by up to +-3 px (+-2 for the hand), gives one score per class; those scores and the shape features
form the feature vector, classified by its nearest labelled examples (k-NN, standardised features)
or, for the hand, by a small neural network ensemble.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

import cv2
import numpy as np

from assistbot.errors import UserError

ROOT = Path(__file__).resolve().parents[3] / "assets" / "templates"
PROTOTYPES = 2
KINDS = {"bottle": ("closed", "open"), "glass": ("inverted", "empty", "full"),
         "hand": ("none", "reach", "grasp_ag", "grasp_sg", "open_palm_request", "pointing", "remove_stopper", "pour", "drink")}
K_NEIGHBOURS = 5


_SHIFT = 3
#: a smaller shift range for the hand's 24x24 crops (9 classes x 2 prototypes: the largest matrix)
SHIFT = {"hand": 2}
_WINDOWS: dict[int, tuple] = {}


def _windows(protos: list[list[np.ndarray]], shift: int = _SHIFT) -> tuple[np.ndarray, np.ndarray]:
    """Every prototype shifted by -shift..+shift px (zeros shifted in), each window centred and
    scaled to unit norm: ((windows, pixels) matrix, class per window).  Computed once per library."""
    key = (id(protos), shift)
    if key not in _WINDOWS:
        rows, cls = [], []
        for c, plist in enumerate(protos):
            for p in plist:
                h, w = p.shape
                pad = np.zeros((h + 2 * shift, w + 2 * shift), np.float32)
                pad[shift:shift + h, shift:shift + w] = p
                for dy in range(2 * shift + 1):
                    for dx in range(2 * shift + 1):
                        win = pad[dy:dy + h, dx:dx + w].ravel().astype(np.float64)
                        win = win - win.mean()
                        n = np.linalg.norm(win)
                        rows.append(win / n if n > 1e-9 else np.zeros_like(win))
                        cls.append(c)
        W = np.array(rows, np.float32) if rows else np.zeros((0, 1), np.float32)
        _WINDOWS[key] = (W, np.array(cls, int), protos)   # protos kept: the id stays theirs
    W, cls, _ = _WINDOWS[key]
    return W, cls


def template_scores(crop: np.ndarray | None, protos: list[list[np.ndarray]], shift: int = _SHIFT) -> np.ndarray:
    """Best normalised match (TM_CCOEFF_NORMED: correlation of the mean-free crop and window over their
    norms) of crop against each class's prototypes shifted by up to +-shift px: one score per class.  The
    shifted prototypes are precomputed, normalised, as the rows of one matrix, so matching is one
    matrix-vector product (what cv2.matchTemplate of the crop over a mosaic of the prototypes computes,
    at the same positions, at a fraction of the cost).  Crops are normalised to the template size by the
    detector (their size follows the object's distance), so one scale suffices."""
    if crop is None or not any(protos):
        return np.zeros(0, np.float32)
    W, cls = _windows(protos, shift)
    t = crop.ravel().astype(np.float32)
    t = t - t.mean()
    n = float(np.sqrt(t @ t))
    out = np.full(len(protos), -1.0, np.float32)
    if n < 1e-6:                # a constant crop matches nothing
        return out
    r = np.einsum("ij,j->i", W, t / n)     # numpy's own loop: a threaded BLAS call costs more on a busy machine
    np.maximum.at(out, cls, r)
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
    pca: tuple[np.ndarray, np.ndarray] | None = None   # (mean, components): the crop's principal components as features

    def features(self, crop: np.ndarray | None, extra: np.ndarray) -> np.ndarray:
        parts = [template_scores(crop, self.protos, SHIFT.get(self.kind, _SHIFT))]
        if self.pca is not None:
            parts.append(_project(crop, self.pca))
        parts.append(np.asarray(extra, np.float32))
        return np.concatenate(parts)

    def classify(self, crop: np.ndarray | None, extra: np.ndarray) -> tuple[str, float, np.ndarray]:
        """(class, confidence in [0, 1], class template scores)."""
        f = self.features(crop, extra)
        z = (f - self.mean) / self.std * self.weights
        if self.mlp is not None:   # an ensemble: the members' probabilities averaged
            m = self.mlp
            h = np.tanh(np.einsum("f,mfh->mh", z, m["W1"]) + m["b1"])
            logit = np.einsum("mh,mhc->mc", h, m["W2"]) + m["b2"]
            pr = np.exp(logit - logit.max(axis=1, keepdims=True))
            pr = (pr / pr.sum(axis=1, keepdims=True)).mean(axis=0)
            c = int(np.argmax(pr))
            return self.classes[c], float(pr[c]), f[:len(self.protos)]
        d = np.sum((self.X - z) ** 2, axis=1)
        idx = np.argpartition(d, min(K_NEIGHBOURS, len(d) - 1))[:K_NEIGHBOURS]
        w = 1.0 / (np.sqrt(d[idx]) + 1e-3)
        votes = np.bincount(self.y[idx], weights=w, minlength=len(self.classes))
        c = int(np.argmax(votes))
        return self.classes[c], float(votes[c] / votes.sum()), f[:len(self.protos)]


def build_classifier(kind: str, crops: list[np.ndarray | None], extras: list[np.ndarray], labels: list[str], seed: int = 0,
                     weights: np.ndarray | None = None) -> Classifier:
    classes = KINDS[kind]
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
    pca = None
    if kind in PCA_KINDS:
        pca = _fit_pca([cr for cr in crops if cr is not None], PCA_COMPONENTS)
    probe = Classifier(kind, classes, protos_f, np.zeros((0, 1), np.float32), y, np.zeros(1), np.ones(1), np.ones(1), None, pca)
    F = np.array([probe.features(cr, e) for cr, e in zip(crops, extras)], np.float32)
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
    return Classifier(kind, classes, protos_f, Z, y, mean, std, w, mlp, pca)


PCA_KINDS = ("hand",)
PCA_COMPONENTS = 20         # the hand crop's leading principal components: the outline's shape beyond the class templates


def _fit_pca(crops: list[np.ndarray], k: int) -> tuple[np.ndarray, np.ndarray]:
    """Mean and the k leading principal axes of the crops (as stored: rounded to 5 decimals)."""
    X = np.array([c.ravel() for c in crops], np.float64)
    mu = X.mean(0)
    _, _, Vt = np.linalg.svd(X - mu, full_matrices=False)
    V = Vt[:k] * np.sign(Vt[:k, :1] + 1e-12)       # a fixed sign per axis
    return np.round(mu, 5).astype(np.float32), np.round(V, 5).astype(np.float32)


def _project(crop: np.ndarray | None, pca: tuple[np.ndarray, np.ndarray]) -> np.ndarray:
    mu, V = pca
    if crop is None:
        return np.zeros(len(V), np.float32)
    return np.einsum("ij,j->i", V, crop.ravel().astype(np.float32) - mu)   # no BLAS call (its threads: see template_scores)


MLP_KINDS = ("hand",)
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
        if clf.pca is not None:
            entry["pca"] = {"mean": _r(clf.pca[0]), "components": [_r(v) for v in clf.pca[1]]}
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
    path = (root or ROOT) / "calibration.json"
    if not path.exists():
        raise UserError(str(path), "calibration", "missing colour calibration; run `assistbot calibrate` (or `assistbot templates`, which also calibrates)")
    return json.loads(path.read_text())


def load(root: Path | None = None) -> tuple[dict[str, Classifier], dict]:
    """The classifiers and the calibration from assets/templates/ (UserError if missing)."""
    root = root or ROOT
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
        pca = None
        if "pca" in e:
            pca = (np.array(e["pca"]["mean"], np.float32), np.array(e["pca"]["components"], np.float32))
        out[kind] = Classifier(kind, tuple(e["classes"]), protos, X, np.array(e["examples"]["y"], int),
                               np.array(e["mean"], np.float32), np.array(e["std"], np.float32), np.array(e["weights"], np.float32), mlp, pca)
    return out, load_calibration(root)
