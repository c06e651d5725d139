"""Compares nenrin's render of a scene with Blender's render of its twin (scene-linear EXR):
the mean brightness, the RMSE, and the coat highlight (pixels brighter than 3x the image's
median luminance: present in both, in the same place). Prints the figures; exits 1 if one is
past its threshold.

python3 compare_twin.py NENRIN.exr BLENDER.exr MAX_MEAN_DIFF MAX_RMSE MAX_HIGHLIGHT_SHIFT_PX
"""

import sys

import numpy as np
import OpenImageIO as oiio


def rgb(path):
    buf = oiio.ImageBuf(path)
    if buf.has_error:
        sys.exit(f"compare_twin: {path}: {buf.geterror()}")
    spec = buf.spec()
    names = list(spec.channelnames)
    pixels = buf.get_pixels(oiio.FLOAT)
    return np.stack([pixels[..., names.index(c)] for c in "RGB"], axis=-1)


def luminance(image):
    return image @ np.array([0.2126, 0.7152, 0.0722])


def highlight(image):
    lum = luminance(image)
    mask = lum > 3 * np.median(lum)
    ys, xs = np.nonzero(mask)
    centre = (xs.mean(), ys.mean()) if len(xs) else (float("nan"), float("nan"))
    return int(mask.sum()), centre, float(lum[mask].mean()) if len(xs) else 0.0


def main(nenrin_path, blender_path, max_mean, max_rmse, max_shift):
    a, b = rgb(nenrin_path), rgb(blender_path)
    if a.shape != b.shape:
        sys.exit(f"compare_twin: sizes differ: {a.shape} vs {b.shape}")
    mean_a, mean_b = float(a.mean()), float(b.mean())
    mean_diff = abs(mean_a - mean_b) / mean_a
    rmse = float(np.sqrt(((a - b) ** 2).mean()))
    n_a, c_a, l_a = highlight(a)
    n_b, c_b, l_b = highlight(b)
    shift = float(np.hypot(c_a[0] - c_b[0], c_a[1] - c_b[1]))
    print(f"mean: nenrin {mean_a:.4f}, Blender {mean_b:.4f}, relative difference "
          f"{mean_diff:.3f} (limit {max_mean})")
    print(f"RMSE {rmse:.4f} (limit {max_rmse}, relative to the mean {rmse / mean_a:.3f})")
    print(f"coat highlight: nenrin {n_a} px, mean luminance {l_a:.2f}, centre "
          f"({c_a[0]:.1f}, {c_a[1]:.1f}); Blender {n_b} px, {l_b:.2f}, "
          f"({c_b[0]:.1f}, {c_b[1]:.1f}); shift {shift:.1f} px (limit {max_shift})")
    failures = []
    if not mean_diff <= max_mean:
        failures.append("mean")
    if not rmse <= max_rmse:
        failures.append("RMSE")
    if n_a < 50 or n_b < 50:
        failures.append("highlight missing")
    if not shift <= max_shift:
        failures.append("highlight position")
    if failures:
        print("FAIL: " + ", ".join(failures))
        sys.exit(1)
    print("PASS")


if __name__ == "__main__":
    if len(sys.argv) != 6:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2], *map(float, sys.argv[3:]))
