#!/usr/bin/env python3
"""`nenrin stats` against the team's reference script ../shared/tools/photo-stats: the same
figures within 5 % on the six Mokume photographs (H11 and CN03 faces A, B, E), on nenrin bakes
of the faces that are compared with them (--against), on photographs (PNG, JPEG) and a bake
that are not 256 x 256 (resampled by OpenImageIO, where the script uses PIL), and for ring
agreement (--rings). Prints the worst
relative difference per figure.

A figure's relative difference is |nenrin - script| / max(|script|, floor): the floor (1 for
L*a*b*, dE and degrees, 0.01 for the rest) keeps figures that are near 0 by nature, such as
dir_spread_diff, from turning a last-digit rounding into a large ratio.

Usage: photo_stats_agreement_test.py NENRIN SOURCE_DIR WORK_DIR
Exit 77 (skipped) when ../shared (the photographs and the script) is not beside the checkout or
/usr/bin/python3 lacks the script's modules."""
import json
import os
import re
import subprocess
import sys

TOLERANCE = 0.05
PYTHON = "/usr/bin/python3"
VERBOSE = os.environ.get("NENRIN_STATS_VERBOSE") == "1"  # every figure of every case
PHOTOS = ["H11/A", "H11/B", "H11/E", "CN03/A", "CN03/B", "CN03/E"]
# Bakes of the faces the Mokume photographs show (../shared/data/mokume/README.md): name,
# species, origin, right, up, resolution, the photo it is held against.
BAKES = [
    ("hinoki-flat", "hinoki", "0.08,-0.025,0.975", "0,0.05,0", "0,0,0.05", "256x256", "H11/A"),
    ("hinoki-quarter", "hinoki", "0.055,0,0.975", "0.05,0,0", "0,0,0.05", "256x256", "H11/E"),
    ("chestnut-end", "chestnut", "0.055,-0.025,1.0", "0.05,0,0", "0,0.05,0", "256x256", "CN03/B"),
    ("chestnut-flat", "chestnut", "0.08,-0.025,0.975", "0,0.05,0", "0,0,0.05", "256x256",
     "CN03/A"),
    # Not 256 x 256: nenrin resamples with OpenImageIO's triangle filter, the script with PIL's.
    ("hinoki-flat-400", "hinoki", "0.08,-0.025,0.975", "0,0.05,0", "0,0,0.05", "400x400",
     "H11/A"),
]
FLOORS = {"L*": 1, "a*": 1, "b*": 1, "dE_ab": 1, "dir_spread": 1, "dir_spread_diff": 1,
          "median_deg": 1}


def figures(record):
    """Every figure of a JSON line of either tool, by name."""
    out = {}
    if "lab" in record:
        out.update(zip(["L*", "a*", "b*"], record["lab"]))
    for key in ("std_L", "fine", "mid", "dir_spread", "fine_aniso", "median_deg", "within_15deg"):
        if key in record:
            out[key] = record[key]
    out.update(record.get("vs", {}))
    return out


def relative(ours, ref, name):
    return abs(ours - ref) / max(abs(ref), FLOORS.get(name, 0.01))


def run_both(nenrin, script, args):
    """The JSON lines of `nenrin stats ARGS --json` and `photo-stats ARGS --json`, and the text
    lines of both."""
    ours = subprocess.run([nenrin, "stats", "--json"] + args, check=True, capture_output=True,
                          text=True).stdout
    ref = subprocess.run([PYTHON, script, "--json"] + args, check=True, capture_output=True,
                         text=True).stdout
    ours_text = subprocess.run([nenrin, "stats"] + args, check=True, capture_output=True,
                               text=True).stdout
    ref_text = subprocess.run([PYTHON, script] + args, check=True, capture_output=True,
                              text=True).stdout
    return ([json.loads(l) for l in ours.splitlines()], [json.loads(l) for l in ref.splitlines()],
            ours_text.splitlines(), ref_text.splitlines())


def shape(line):
    """A text line with its numbers blanked: both tools must print the same shape."""
    return re.sub(r"[+-]?\d+(\.\d+)?", "#", line)


def compare(label, ours, ref, worst, failures):
    for name, value in figures(ref).items():
        mine = figures(ours).get(name)
        if mine is None:
            failures.append(f"{label}: nenrin has no {name}")
            continue
        r = relative(mine, value, name)
        if r > worst.get(name, (-1, ""))[0]:
            worst[name] = (r, f"{label} ({mine} vs {value})")
        if VERBOSE:
            print(f"  {label:28s} {name:17s} {mine:10g} {value:10g} {100 * r:7.3f} %")
        if r > TOLERANCE:
            failures.append(f"{label}: {name} {mine} vs the script's {value} ({100 * r:.1f} %)")


def bake(nenrin, source, work, name, species, origin, right, up, res):
    exr = os.path.join(work, f"{name}.exr")
    subprocess.run([nenrin, "bake", "slice", "--skeleton",
                    os.path.join(source, "scenes/skeletons/straight-trunk.json"), "--grain",
                    os.path.join(source, f"scenes/grain/species/{species}.json"), "--origin",
                    origin, "--right", right, "--up", up, "--res", res, "-q", "-o", exr],
                   check=True, stdout=subprocess.DEVNULL)
    return exr


def main(nenrin, source, work):
    shared = os.path.normpath(os.path.join(source, "..", "shared"))
    script = os.path.join(shared, "tools", "photo-stats")
    photos = os.path.join(shared, "data", "mokume")
    if not (os.path.isfile(script) and os.path.isdir(photos)):
        print(f"SKIPPED: no {script} or {photos} beside the checkout")
        return 77
    probe = subprocess.run([PYTHON, "-c", "import numpy, scipy, PIL, OpenImageIO"],
                           capture_output=True, text=True)
    if probe.returncode != 0:
        print(f"SKIPPED: {PYTHON} cannot import the script's modules: {probe.stderr.strip()}")
        return 77
    os.makedirs(work, exist_ok=True)
    photo = {p: os.path.join(photos, f"{p}_col.png") for p in PHOTOS}
    worst, failures = {}, []

    # Not 256 x 256 either: the H11 A photograph resized by PIL (bicubic) to 400 x 400 (PNG),
    # 300 x 200 (PNG: enlarged one way, shrunk the other) and 1000 x 1000 (JPEG), which nenrin
    # resamples back with OpenImageIO's lanczos3, the script with PIL's LANCZOS.
    resized = {"H11/A-400": ("png", 400, 400), "H11/A-300x200": ("png", 300, 200),
               "H11/A-1000": ("jpg", 1000, 1000)}
    for name, (ext, w, h) in resized.items():
        photo[name] = os.path.join(work, f"{name.replace('/', '-')}.{ext}")
        subprocess.run([PYTHON, "-c", "import sys; from PIL import Image; Image.open(sys.argv[1])"
                        ".resize((int(sys.argv[3]), int(sys.argv[4])), Image.BICUBIC)"
                        ".save(sys.argv[2])", photo["H11/A"], photo[name], str(w), str(h)],
                       check=True)
    names = PHOTOS + list(resized)
    ours, ref, ours_text, ref_text = run_both(nenrin, script, [photo[p] for p in names])
    for p, o, r in zip(names, ours, ref):
        compare(p, o, r, worst, failures)
    for o, r in zip(ours_text, ref_text):
        if shape(o) != shape(r):
            failures.append(f"text lines differ in shape:\n  {o}\n  {r}")

    for name, species, origin, right, up, res, against in BAKES:
        exr = bake(nenrin, source, work, name, species, origin, right, up, res)
        ours, ref, ours_text, ref_text = run_both(nenrin, script,
                                                  ["--against", photo[against], exr])
        compare(f"{name} vs {against}", ours[1], ref[1], worst, failures)
        if shape(ours_text[1]) != shape(ref_text[1]):
            failures.append(f"text lines differ in shape:\n  {ours_text[1]}\n  {ref_text[1]}")
        if res == "256x256" and species in ("hinoki", "chestnut") and "flat" in name:
            ours, ref, _, _ = run_both(nenrin, script, ["--rings", photo[against], exr])
            compare(f"rings {name} vs {against}", ours[0], ref[0], worst, failures)

    print(f"worst relative difference per figure (tolerance {100 * TOLERANCE:.0f} %):")
    for name, (r, where) in worst.items():
        print(f"  {name:17s} {100 * r:6.3f} %  {where}")
    if failures:
        print("FAILED:\n  " + "\n  ".join(failures))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:4]))
