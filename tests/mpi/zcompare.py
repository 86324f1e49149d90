#!/usr/bin/env python3
"""z-test of two Monte Carlo images that estimate the same picture: A.pfm A_var.pfm B.pfm B_var.pfm
[BLOCK] (means and per-pixel variances of the mean, as `amrvk render -o X --variance V` writes
them). Pixels are summed into BLOCKxBLOCK blocks (default 1; their variances add) and each block
gives z = (a - b) / sqrt(var_a + var_b) on the green channel (one channel: the channels of a sample
are correlated). Prints JSON: the number of z values, the chi-square excess
(sum z^2 - n) / sqrt(2 n) (about N(0, 1) when the images agree), the largest |z|, the pooled
z = sum(a - b) / sqrt(sum(var_a + var_b)) (a bias of one sign), and whether they agree (excess < 4,
max |z| < 6, |pooled z| < 4, and every block whose variance is 0 in both images equal in both).
Blocks of variance 0 in both (every sample the same: the background, an empty TF) have no z; they
are compared exactly instead ("zeroVariance": how many, "zeroVarianceDiffer": how many differ,
"zeroVarianceMaxDiff": the largest |a - b|), so a wrong constant background fails.
Exit status 0 when they agree, 1 when not."""
import json
import sys

import numpy as np


def pfm(path):
    with open(path, "rb") as f:
        assert f.readline().strip() == b"PF", path
        w, h = map(int, f.readline().split())
        scale = float(f.readline())
        return np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4").reshape(h, w, 3).astype(np.float64)


def blocks(image, b):
    h, w, _ = image.shape
    return image[: h - h % b, : w - w % b].reshape(h // b, b, w // b, b, 3).sum(axis=(1, 3))


def main():
    a, va, b, vb = (pfm(p) for p in sys.argv[1:5])
    size = int(sys.argv[5]) if len(sys.argv) > 5 else 1
    sa, sva, sb, svb = (blocks(x, size)[..., 1] for x in (a, va, b, vb))
    var = sva + svb
    keep = var > 0
    # Variance 0 in both: the same value in every sample, so the means must be equal. Equal up to
    # float rounding: one deterministic value summed over the samples (double-float sums, then a
    # float mean; data-parallel adds the ranks' sums) comes back within a few float ulps (1.2e-7
    # each), far inside 1e-6 of its magnitude, while any real error in a constant (a background of
    # 0.999 for 1) is far outside it; the 1e-9 absolute allows for values of 0.
    same = ~keep
    diff = np.abs(sa - sb)[same]
    differ = diff > 1e-6 * np.maximum(np.abs(sa), np.abs(sb))[same] + 1e-9
    zeros, zeros_differ = int(same.sum()), int(differ.sum())
    z = (sa - sb)[keep] / np.sqrt(var[keep])
    n = int(z.size)
    excess = float((np.sum(z * z) - n) / np.sqrt(2 * n)) if n else 0.0
    maxz = float(np.max(np.abs(z))) if n else 0.0
    # Pooled: a bias of one sign over many pixels, which the per-pixel test hardly sees.
    pooled = float(np.sum((sa - sb)[keep]) / np.sqrt(np.sum(var[keep]))) if n else 0.0
    agree = n + zeros > 0 and excess < 4 and maxz < 6 and abs(pooled) < 4 and zeros_differ == 0
    print(json.dumps({"n": n, "chi2Excess": round(excess, 3), "maxAbsZ": round(maxz, 3), "pooledZ": round(pooled, 3),
                      "zeroVariance": zeros, "zeroVarianceDiffer": zeros_differ,
                      "zeroVarianceMaxDiff": float(diff.max()) if zeros else 0.0, "agree": agree,
                      "meanA": float(a.mean()), "meanB": float(b.mean())}))
    return 0 if agree else 1


if __name__ == "__main__":
    sys.exit(main())
