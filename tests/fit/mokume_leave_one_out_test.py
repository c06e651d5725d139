#!/usr/bin/env python3
"""The fit judged on faces it never saw (issue 31): each face of the two Mokume cubes
(../shared/data/mokume) left out in turn, the other five fitted (`nenrin fit --leave-out`,
the matching species preset as base), and the left-out face's ring agreement read from
fit.json (`faces[].ring_median_deg`, as `nenrin stats --rings` measures it: the median angle
between the photo's ring normals and the fitted field's grad T).

The issue's goal, a median of at most 8 degrees over each cube's six faces and none over 20,
is not met yet (docs/fit.md); this test holds the figures reached so that a change cannot lose
them unseen: per cube, the median and the worst face under the bounds below (today's figures
plus 1-2 degrees), and prints all twelve; and that each fit's warnings about its pith line
describe the line it kept.

Usage: mokume_leave_one_out_test.py NENRIN SOURCE_DIR WORK_DIR
Exit 77 (skipped) when ../shared (the photographs) is not beside the checkout."""
import concurrent.futures
import json
import os
import re
import statistics
import subprocess
import sys

# cube, base grain, bound on the median, bound on the worst face (degrees). Measured when
# written: H11 6.1 8.9 12.2 9.1 3.5 14.4 (median 9.0); CN03 24.7 9.9 13.1 10.3 13.9 19.9 (13.5).
CUBES = [("H11", "hinoki", 10.0, 16.0), ("CN03", "chestnut", 14.5, 26.0)]
GOAL_MEDIAN, GOAL_WORST = 8.0, 20.0


def held_out_figure(nenrin, sample, grain, face, out):
    subprocess.run([nenrin, "fit", sample, "--grain", grain, "--leave-out", face, "-o", out,
                    "--threads", "1"], check=True, stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL)
    with open(os.path.join(out, "fit.json")) as f:
        report = json.load(f)
    held = [x for x in report["faces"] if x["held_out"]]
    if [x["name"] for x in held] != [face]:
        raise RuntimeError(f"{out}/fit.json: expected face {face} alone held out")
    return held[0]["ring_median_deg"], warning_problems(report, out)


def warning_problems(report, out):
    """The pith's warnings describe the line kept: a misfit warning exactly when its misfit is
    over 20 degrees, a far-pith warning exactly when it lies over 1 m away, each with its
    figure. (They once judged the first line, before the knots' rings were left out: H11 with
    D left out warned of a 27.7 degree misfit where the line kept fits to 7.2.)"""
    pith, problems = report["pith"], []
    for key, limit, pattern, digits in [
            ("median_misfit_deg", 20, r"not cylinders around one pith line: median misfit "
                                      r"([0-9.]+) degrees", 1),
            ("distance", 1.0, r"the pith lies ([0-9.]+) m away", 2)]:
        said = [float(m.group(1)) for w in report["warnings"] for m in [re.search(pattern, w)]
                if m]
        if (pith[key] > limit) != bool(said):
            problems.append(f"{out}: pith {key} {pith[key]}, warnings {report['warnings']}")
        elif said and abs(said[0] - pith[key]) > 0.6 * 10 ** -digits:
            problems.append(f"{out}: warning says {said[0]}, pith {key} is {pith[key]}")
    return problems


def main(nenrin, source, work):
    photos = os.path.normpath(os.path.join(source, "..", "shared", "data", "mokume"))
    if not os.path.isdir(photos):
        print(f"SKIPPED: no {photos} beside the checkout")
        return 77
    os.makedirs(work, exist_ok=True)
    jobs = {}
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, os.cpu_count() or 1)) as pool:
        for cube, species, _, _ in CUBES:
            sample = os.path.join(photos, cube, "sample.json")
            grain = os.path.join(source, "scenes", "grain", "species", f"{species}.json")
            for face in "ABCDEF":
                out = os.path.join(work, f"loo-{cube}-{face}")
                jobs[cube, face] = pool.submit(held_out_figure, nenrin, sample, grain, face, out)
    failures = []
    for cube, _, median_bound, worst_bound in CUBES:
        results = [jobs[cube, face].result() for face in "ABCDEF"]
        figures = [figure for figure, _ in results]
        failures += [p for _, problems in results for p in problems]
        median, worst = statistics.median(figures), max(figures)
        print(f"{cube} left out: " + " ".join(f"{face} {v:.1f}" for face, v in
                                               zip("ABCDEF", figures)) +
              f"; median {median:.1f}, worst {worst:.1f} (issue's goal: median <= {GOAL_MEDIAN:g},"
              f" none over {GOAL_WORST:g}: {'met' if median <= GOAL_MEDIAN and worst <= GOAL_WORST else 'not met'})")
        if median > median_bound:
            failures.append(f"{cube}: median {median:.1f} over {median_bound}")
        if worst > worst_bound:
            failures.append(f"{cube}: worst face {worst:.1f} over {worst_bound}")
    for f in failures:
        print("FAILED:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:4]))
