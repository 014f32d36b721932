"""The template library: class prototypes (small PNGs) and labelled feature examples (index.json).

Built by `assistbot templates` from scenes of the "library" seed stream (never scored).  For
each classified thing — the bottle's state, the glass's state, the hand's posture — the
library keeps, per class, up to `PROTOTYPES` prototype templates (means of k-means clusters
of the examples' crops) and the examples' feature vectors.  Classification of a new crop:
`cv2.matchTemplate` (normalised correlation coefficient) of the crop against every prototype
at three scales gives one score per class; those scores and the shape features form the
feature vector, classified by its nearest labelled examples (k-NN, standardised features).
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

import cv2
import numpy as np

from assistbot.errors import UserError

ROOT = Path(__file__).resolve().parents[3] / "assets" / "templates"
PROTOTYPES = 3
SCALES = (0.9, 1.0, 1.1)
KINDS = {"bottle": ("closed", "open"), "glass": ("inverted", "empty", "full"),
         "hand": ("none", "reach", "grasp_ag", "grasp_sg", "open_palm_request", "pointing")}
K_NEIGHBOURS = 5


def _pad(crop: np.ndarray) -> np.ndarray:
    return cv2.copyMakeBorder(crop.astype(np.float32), 3, 3, 3, 3, cv2.BORDER_CONSTANT, value=0)


def template_scores(crop: np.ndarray, protos: list[list[np.ndarray]]) -> np.ndarray:
    """Best normalised match of crop against each class's prototypes over SCALES (one score per class)."""
    out = np.full(len(protos), -1.0, np.float32)
    h, w = crop.shape
    scaled = [_pad(cv2.resize(crop, (max(4, int(round(w * s))), max(4, int(round(h * s)))), interpolation=cv2.INTER_LINEAR)) for s in SCALES]
    for c, plist in enumerate(protos):
        best = -1.0
        for p in plist:
            for img in scaled:
                if img.shape[0] < p.shape[0] or img.shape[1] < p.shape[1]:
                    continue
                r = cv2.matchTemplate(img, p, cv2.TM_CCOEFF_NORMED)
                best = max(best, float(r.max()))
        out[c] = best
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

    def features(self, crop: np.ndarray, extra: np.ndarray) -> np.ndarray:
        return np.concatenate([template_scores(crop, self.protos), np.asarray(extra, np.float32)])

    def classify(self, crop: np.ndarray, extra: np.ndarray) -> tuple[str, float, np.ndarray]:
        """(class, confidence in [0, 1], class template scores)."""
        f = self.features(crop, extra)
        z = (f - self.mean) / self.std * self.weights
        d = np.sum((self.X - z) ** 2, axis=1)
        idx = np.argpartition(d, min(K_NEIGHBOURS, len(d) - 1))[:K_NEIGHBOURS]
        w = 1.0 / (np.sqrt(d[idx]) + 1e-3)
        votes = np.bincount(self.y[idx], weights=w, minlength=len(self.classes))
        c = int(np.argmax(votes))
        return self.classes[c], float(votes[c] / votes.sum()), f[:len(self.classes)]


def build_classifier(kind: str, crops: list[np.ndarray], extras: list[np.ndarray], labels: list[str], seed: int = 0,
                     weights: np.ndarray | None = None) -> Classifier:
    classes = KINDS[kind]
    y = np.array([classes.index(lab) for lab in labels])
    protos = []
    for c in range(len(classes)):
        sel = [cr for cr, yy in zip(crops, y) if yy == c]
        if not sel:
            protos.append([])
            continue
        X = np.array([s.ravel() for s in sel])
        lab = kmeans(X, PROTOTYPES, seed + c)
        protos.append([_to_u8(X[lab == j].mean(0).reshape(sel[0].shape)) for j in range(lab.max() + 1)])
    protos_f = [[p.astype(np.float32) / 255.0 for p in pl] for pl in protos]
    F = np.array([np.concatenate([template_scores(cr, protos_f), e]) for cr, e in zip(crops, extras)], np.float32)
    mean, std = F.mean(0), F.std(0) + 1e-3
    w = np.ones(F.shape[1], np.float32) if weights is None else np.asarray(weights, np.float32)
    return Classifier(kind, classes, protos_f, (F - mean) / std * w, y, mean, std, w)


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
        protos = [[cv2.imread(str(root / n), cv2.IMREAD_GRAYSCALE).astype(np.float32) / 255.0 for n in e["prototypes"][c]] for c in e["classes"]]
        X = np.array(e["examples"]["X"], np.float32)
        out[kind] = Classifier(kind, tuple(e["classes"]), protos, X, np.array(e["examples"]["y"]),
                               np.array(e["mean"], np.float32), np.array(e["std"], np.float32), np.array(e["weights"], np.float32))
    return out, load_calibration(root)
